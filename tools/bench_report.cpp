#include "bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {
namespace {

// Writes through a temporary file renamed over `path`, as every ssrcl output.
void writeText(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.good()) {
      std::filesystem::remove(tmp);
      throw Error(ErrorCode::IoError, path + ": cannot write");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw Error(ErrorCode::IoError, path + ": cannot write (" + ec.message() + ")");
  }
}

// Axis labels: 0.05, 2, 1000 (no trailing zeros).
std::string number(double v) {
  if (v >= 1) return std::to_string(std::llround(v));
  std::ostringstream o;
  o << std::setprecision(3) << v;
  return o.str();
}

std::string escapeXml(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

}  // namespace

void printBenchTable(std::ostream& out, const std::vector<BenchResult>& results, const std::string& device) {
  out << "device: " << device << "\n";
  std::string input;
  for (const BenchResult& r : results) {
    if (r.input != input) {
      input = r.input;
      out << "\n"
          << input << " (" << r.width << "x" << r.height << ", " << std::fixed << std::setprecision(1)
          << 100.0 * r.pixelsTraced / (double(r.width) * r.height) << "% of pixels traced, "
          << 100.0 * r.tilesResolved / (double((r.width + 7) / 8) * ((r.height + 7) / 8))
          << "% of 8x8 tiles resolved at the first setting)\n"
          << std::left << std::setw(26) << "config" << std::right << std::setw(10) << "total ms" << std::setw(10)
          << "setup" << std::setw(8) << "hzb" << std::setw(10) << "trace" << std::setw(10) << "resolve" << std::setw(9)
          << "filter" << std::setw(11) << "Mrays/s" << std::setw(10) << "fetch/ray" << std::setw(9) << "MiB/MP"
          << std::setw(11) << "Mrays" << std::setw(9) << "RMSE" << std::setw(8) << "PSNR" << std::setw(7) << ">5%"
          << "\n";
    }
    auto median = [&](const char* stage) {
      auto it = r.stages.find(stage);
      return it == r.stages.end() ? 0.0 : it->second.medianMs;
    };
    out << std::left << std::setw(26) << r.config << std::right << std::fixed << std::setprecision(1) << std::setw(10)
        << median("total") << std::setw(10) << median("setup") << std::setw(8) << median("hzb") << std::setw(10)
        << median("trace") << std::setw(10) << median("resolve") << std::setw(9) << median("denoise")
        << std::setprecision(2) << std::setw(11) << r.raysPerSecond * 1e-6 << std::setprecision(1) << std::setw(10)
        << r.fetchesPerRay << std::setw(9) << r.deviceMiBPerMegapixel << std::setprecision(3) << std::setw(11)
        << r.rays * 1e-6;
    if (r.hasError)
      out << std::setprecision(4) << std::setw(9) << r.error.rmse << std::setprecision(1) << std::setw(8)
          << r.error.psnr << std::setw(6) << 100 * r.error.fractionOver5Percent << "%";
    out << "\n";
  }
  out << "\nTimes are medians of device time per stage (OpenCL profiling events); total includes upload and\n"
         "download. Error is against the reference preset over reflecting pixels.\n";
}

void writeBenchJson(const std::string& path, const std::vector<BenchResult>& results, const std::string& device) {
  nlohmann::json j;
  j["device"] = device;
  j["results"] = nlohmann::json::array();
  for (const BenchResult& r : results) {
    nlohmann::json e = {{"input", r.input},
                        {"config", r.config},
                        {"width", r.width},
                        {"height", r.height},
                        {"pixels_traced", r.pixelsTraced},
                        {"tiles_resolved", r.tilesResolved},
                        {"rays", r.rays},
                        {"rays_per_second", r.raysPerSecond},
                        {"depth_fetches_per_ray", r.fetchesPerRay},
                        {"iteration_histogram", r.iterationHistogram},
                        {"device_mib_per_megapixel", r.deviceMiBPerMegapixel}};
    for (const auto& [stage, s] : r.stages) e["stages_ms"][stage] = {{"min", s.minMs}, {"median", s.medianMs}};
    if (r.hasError)
      e["error_vs_reference"] = {
          {"rmse", r.error.rmse}, {"psnr_db", r.error.psnr}, {"fraction_over_5_percent", r.error.fractionOver5Percent}};
    j["results"].push_back(e);
  }
  writeText(path, j.dump(2) + "\n");
}

void writeBenchSvg(const std::string& path, const std::vector<BenchResult>& results, const std::string& device,
                   const std::string& errorAxis) {
  std::vector<const BenchResult*> points;
  for (const BenchResult& r : results)
    if (r.hasError && r.error.rmse > 0 && r.stages.count("total")) points.push_back(&r);
  if (points.empty()) throw Error(ErrorCode::InvalidArgument, path + ": no errors measured to plot (reference off?)");
  double tMin = INFINITY, tMax = 0, eMin = INFINITY, eMax = 0;
  for (const BenchResult* r : points) {
    const double t = r->stages.at("total").medianMs, e = r->error.rmse;
    tMin = std::min(tMin, t), tMax = std::max(tMax, t), eMin = std::min(eMin, e), eMax = std::max(eMax, e);
  }
  // Log axes padded by a quarter decade, whole decades labelled.
  const double lt0 = std::log10(tMin) - 0.25, lt1 = std::log10(tMax) + 0.25;
  const double le0 = std::log10(eMin) - 0.25, le1 = std::log10(eMax) + 0.25;
  const double W = 900, H = 600, left = 90, right = 260, top = 50, bottom = 70;
  auto X = [&](double t) { return left + (std::log10(t) - lt0) / (lt1 - lt0) * (W - left - right); };
  auto Y = [&](double e) { return top + (le1 - std::log10(e)) / (le1 - le0) * (H - top - bottom); };
  const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
  std::map<std::string, int> colour;
  for (const BenchResult* r : points) colour.emplace(r->input, int(colour.size()) % 8);

  std::ostringstream s;
  s << std::fixed << std::setprecision(1);
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' font-family='sans-serif' "
    << "font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n"
    << "<text x='" << left << "' y='24' font-size='16'>ssrcl: error against time (lower left is better)</text>\n"
    << "<text x='" << left << "' y='40' fill='#555'>" << escapeXml(device) << "</text>\n"
    << "<rect x='" << left << "' y='" << top << "' width='" << W - left - right << "' height='" << H - top - bottom
    << "' fill='none' stroke='#333'/>\n";
  for (int d = int(std::floor(lt0)); d <= int(std::ceil(lt1)); ++d)
    for (int m = 1; m < 10; ++m) {
      const double t = m * std::pow(10.0, d);
      if (std::log10(t) < lt0 || std::log10(t) > lt1) continue;
      s << "<line x1='" << X(t) << "' y1='" << top << "' x2='" << X(t) << "' y2='" << H - bottom << "' stroke='"
        << (m == 1 ? "#bbb" : "#eee") << "'/>\n";
      if (m == 1 || m == 2 || m == 5)
        s << "<text x='" << X(t) << "' y='" << H - bottom + 16 << "' text-anchor='middle'>" << number(t) << "</text>\n";
    }
  for (int d = int(std::floor(le0)); d <= int(std::ceil(le1)); ++d)
    for (int m = 1; m < 10; ++m) {
      const double e = m * std::pow(10.0, d);
      if (std::log10(e) < le0 || std::log10(e) > le1) continue;
      s << "<line x1='" << left << "' y1='" << Y(e) << "' x2='" << W - right << "' y2='" << Y(e) << "' stroke='"
        << (m == 1 ? "#bbb" : "#eee") << "'/>\n";
      if (m == 1 || m == 2 || m == 5)
        s << "<text x='" << left - 6 << "' y='" << Y(e) + 4 << "' text-anchor='end'>" << number(e) << "</text>\n";
    }
  s << "<text x='" << (left + W - right) / 2 << "' y='" << H - 20 << "' text-anchor='middle'>device time per frame, ms "
    << "(median, log)</text>\n<text transform='translate(24," << (top + H - bottom) / 2
    << ") rotate(-90)' text-anchor='middle'>" << escapeXml(errorAxis) << "</text>\n";
  for (const auto& [input, c] : colour) {
    // Pareto front: points no other point beats in both time and error.
    std::vector<const BenchResult*> mine;
    for (const BenchResult* r : points)
      if (r->input == input) mine.push_back(r);
    std::sort(mine.begin(), mine.end(),
              [](auto* a, auto* b) { return a->stages.at("total").medianMs < b->stages.at("total").medianMs; });
    s << "<polyline fill='none' stroke='" << palette[c] << "' stroke-width='1.5' stroke-dasharray='4 3' points='";
    double best = INFINITY;
    for (const BenchResult* r : mine)
      if (r->error.rmse < best) {
        best = r->error.rmse;
        s << X(r->stages.at("total").medianMs) << "," << Y(r->error.rmse) << " ";
      }
    s << "'/>\n";
    for (size_t k = 0; k < mine.size(); ++k) {
      const double x = X(mine[k]->stages.at("total").medianMs), y = Y(mine[k]->error.rmse);
      // Labels alternate above and below their points so neighbours in time do not overlap.
      s << "<circle cx='" << x << "' cy='" << y << "' r='4' fill='" << palette[c] << "'/>\n"
        << "<text x='" << x + 6 << "' y='" << (k % 2 ? y + 16 : y - 6) << "' fill='" << palette[c] << "'>"
        << escapeXml(mine[k]->config) << "</text>\n";
    }
    s << "<text x='" << W - right + 12 << "' y='" << top + 16 + 18 * c << "' fill='" << palette[c] << "'>"
      << escapeXml(input) << "</text>\n";
  }
  s << "</svg>\n";
  writeText(path, s.str());
}

}  // namespace ssrcl::cli
