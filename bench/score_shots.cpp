// Scores reflection passes of shots (samples/real/make_shots.py: Cycles references of every frame,
// a second seed of the first, EEVEE of every frame) per frame and over time: the mean per-frame
// PSNR and the mean tPSNR (tests/support/shot_metric.hpp) of each configuration, the references'
// noise floor, and frames/s from each batch's report. Passes are compared in the glossy-pass form
// with Cycles' Glossy Direct + Indirect as they are (`ssrcl batch --output-form glossy-pass`);
// EEVEE's Specular Light x Specular Color likewise.
//
//   ssrcl_score_shots --shots out/shots --passes out/shot-passes --configs medium,high,eevee
//       (config C of shot S: <passes>/<C>/<S>/<S>.NNNN.refl.exr and the report <passes>/<C>/<S>.json;
//        "eevee": <shots>/<S>/eevee/<S>.NNNN.exr)
//   --breakdown: where each configuration's temporal error lies (bench/shot_breakdown.hpp; needs
//   the "medium" passes, and "medium-frameseeds" for the blend's unblended pixels)
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "shot_breakdown.hpp"
#include "support/cycles_reference.hpp"
#include "support/shot_metric.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// A shot's frames: <dir>/<shot>.NNNN.exr in name order.
std::vector<std::string> shotFrames(const fs::path& dir, const std::string& shot) {
  std::vector<std::string> frames;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(shot + ".", 0) == 0 && e.path().extension() == ".exr") frames.push_back(e.path().string());
  }
  std::sort(frames.begin(), frames.end());
  if (frames.size() < 2) throw std::runtime_error(dir.string() + ": fewer than 2 frames of " + shot);
  return frames;
}

struct ShotScore {
  bool present = false;
  double psnr = 0, tpsnr = 0, framesPerSecond = 0;
  // tPSNR of the pass's own temporal error: the references' noise (the floor's TE) taken out of
  // each pair's TE in quadrature; NaN without a floor or where a pair's TE is under it.
  double tpsnrAboveNoise = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scores reflection passes of shots per frame and over time against Cycles"};
  std::string shotsDir = "out/shots", passesDir = "out/shot-passes", configList = "medium,eevee", shotList, jsonPath;
  app.add_option("--shots", shotsDir, "Directory of the shots (shots.json, <shot>/ each)")->capture_default_str();
  app.add_option("--passes", passesDir, "Passes: <passes>/<config>/<shot>/<frame stem>.refl.exr")
      ->capture_default_str();
  app.add_option("--configs", configList, "Comma-separated configurations (folder names; eevee: the peer)")
      ->capture_default_str();
  app.add_option("--shot", shotList, "Only these shots (comma-separated)");
  app.add_option("--json", jsonPath, "Write every figure as JSON");
  std::string dumpDir;
  app.add_option(
      "--dump", dumpDir,
      "Write <dump>/<config>.<frame stem>.ppm of every frame after the first: the pass, Cycles, the temporal "
      "error, the references' change and the pass's");
  bool breakdown = false;
  app.add_flag("--breakdown", breakdown, "Print where each configuration's temporal error lies");
  CLI11_PARSE(app, argc, argv);
  try {
    std::ifstream manifest(shotsDir + "/shots.json");
    if (!manifest) throw std::runtime_error(shotsDir + "/shots.json: cannot read");
    std::vector<std::string> shots;
    const std::vector<std::string> only = splitList(shotList);
    const nlohmann::json listed = nlohmann::json::parse(manifest);
    for (const auto& s : listed.at("shots"))
      if (only.empty() || std::find(only.begin(), only.end(), s.at("name")) != only.end())
        shots.push_back(s.at("name"));
    if (shots.empty()) throw std::runtime_error("no shots selected");
    const std::vector<std::string> configs = splitList(configList);
    std::vector<std::vector<ShotScore>> scores(configs.size(), std::vector<ShotScore>(shots.size()));
    std::vector<double> floorT(shots.size()), floorP(shots.size()), floorTe(shots.size());
    nlohmann::json json;
    for (size_t s = 0; s < shots.size(); ++s) {
      const fs::path dir = fs::path(shotsDir) / shots[s];
      const std::vector<std::string> frames = shotFrames(dir, shots[s]);
      std::vector<ssrcl::test::CyclesReference> refs;
      for (const std::string& f : frames) {
        refs.push_back(ssrcl::test::loadCyclesReference(f));
        std::fill(refs.back().scale.begin(), refs.back().scale.end(), 1.0);  // glossy-pass form: Cycles as it is
      }
      const fs::path second = dir / "seed2" / fs::path(frames.front()).filename();
      floorT[s] = floorP[s] = floorTe[s] = NAN;  // no second seed rendered: no floor
      if (fs::exists(second)) {
        const ssrcl::test::TemporalError noise =
            ssrcl::test::noiseFloor(refs.front(), ssrcl::test::loadCyclesReference(second.string()));
        floorT[s] = noise.tpsnr;
        floorTe[s] = noise.te;
        floorP[s] = noise.tpsnr + 20 * std::log10(std::sqrt(2.0));  // one render's noise, sigma, not sqrt(2) sigma
        json["shots"][shots[s]]["noise_floor"] = {{"tpsnr_db", floorT[s]}, {"psnr_db", floorP[s]}};
      }
      // A configuration's passes of this shot, or none where a frame's is missing.
      const auto passesOf = [&](const std::string& config, std::vector<std::string>* paths = nullptr) {
        std::vector<ssrcl::Image> passes;
        for (const std::string& f : frames) {
          const std::string stem = fs::path(f).stem().string();
          const fs::path path = config == "eevee" ? dir / "eevee" / (stem + ".exr")
                                                  : fs::path(passesDir) / config / shots[s] / (stem + ".refl.exr");
          if (!fs::exists(path)) return std::vector<ssrcl::Image>{};
          if (paths) paths->push_back(path.string());
          passes.push_back(config == "eevee" ? ssrcl::test::eeveeSpecular(path.string(), true)
                                             : ssrcl::test::readReflectionPass(path.string()));
        }
        return passes;
      };
      std::vector<std::vector<uint8_t>> classes;
      std::vector<ssrcl::Image> alone;
      if (breakdown) {
        std::vector<std::string> medium;
        if (passesOf("medium", &medium).empty())
          throw std::runtime_error("--breakdown: no medium passes of " + shots[s]);
        classes = ssrcl::bench::classifyPixels(medium);
        alone = passesOf("medium-frameseeds");
      }
      for (size_t c = 0; c < configs.size(); ++c) {
        const bool eevee = configs[c] == "eevee";
        const std::vector<ssrcl::Image> passes = passesOf(configs[c]);
        if (passes.empty()) continue;
        if (breakdown)
          ssrcl::bench::printBreakdown(std::cerr, shots[s] + " " + configs[c], refs, passes, classes,
                                       configs[c].rfind("medium-t", 0) == 0 && !alone.empty() ? &alone : nullptr);
        ShotScore& score = scores[c][s];
        nlohmann::json perFrame = nlohmann::json::array();
        for (size_t t = 0; t < frames.size(); ++t) {
          const double psnr = ssrcl::test::referenceError(refs[t], passes[t], refs[t].groups.front().second).psnr;
          score.psnr += psnr / double(frames.size());
          nlohmann::json frame = {{"frame", fs::path(frames[t]).filename().string()}, {"psnr_db", psnr}};
          if (t > 0 && !dumpDir.empty())
            ssrcl::bench::writeTemporalPanels(
                dumpDir + "/" + configs[c] + "." + fs::path(frames[t]).stem().string() + ".ppm", refs[t - 1],
                passes[t - 1], refs[t], passes[t]);
          if (t > 0) {
            const ssrcl::test::TemporalError te =
                ssrcl::test::temporalError(refs[t - 1], passes[t - 1], refs[t], passes[t]);
            score.tpsnr += te.tpsnr / double(frames.size() - 1);
            const double own = te.te * te.te - floorTe[s] * floorTe[s];
            const double above = own > 0 ? 20 * std::log10(refs[t].peak / std::sqrt(own)) : NAN;
            score.tpsnrAboveNoise += above / double(frames.size() - 1);
            frame["tpsnr_db"] = te.tpsnr;
            frame["tpsnr_above_noise_db"] = above;
            frame["tpsnr_pixels"] = te.pixels;
          }
          perFrame.push_back(frame);
        }
        const fs::path report = fs::path(passesDir) / configs[c] / (shots[s] + ".json");
        if (std::ifstream r(report); !eevee && r)
          score.framesPerSecond = nlohmann::json::parse(r).value("frames_per_second", 0.0);
        score.present = true;
        json["shots"][shots[s]]["configs"][configs[c]] = {{"psnr_db", score.psnr},
                                                          {"tpsnr_db", score.tpsnr},
                                                          {"tpsnr_above_noise_db", score.tpsnrAboveNoise},
                                                          {"frames_per_second", score.framesPerSecond},
                                                          {"frames", perFrame}};
      }
      std::cerr << "scored " << shots[s] << " (" << frames.size() << " frames)\n";
    }
    std::cout << "mean per-frame PSNR / mean tPSNR (tPSNR with the references' noise taken out) in dB against "
                 "Cycles, glossy-pass form; @ frames/s of the batch\n"
              << std::left << std::setw(14) << "config" << std::right;
    for (const std::string& s : shots) std::cout << std::setw(32) << s;
    std::cout << std::setw(16) << "mean\n" << std::fixed << std::setprecision(2);
    const auto row = [&](const std::string& label, const std::function<std::string(size_t)>& cell,
                         const std::string& mean) {
      std::cout << std::left << std::setw(14) << label << std::right;
      for (size_t s = 0; s < shots.size(); ++s) std::cout << std::setw(32) << cell(s);
      std::cout << std::setw(16) << mean << "\n";
    };
    const auto fmt = [](double v, int digits = 2) {
      std::ostringstream o;
      o << std::fixed << std::setprecision(digits) << v;
      return o.str();
    };
    for (size_t c = 0; c < configs.size(); ++c) {
      double p = 0, t = 0;
      size_t n = 0;
      for (size_t s = 0; s < shots.size(); ++s)
        if (scores[c][s].present) p += scores[c][s].psnr, t += scores[c][s].tpsnr, ++n;
      row(
          configs[c],
          [&](size_t s) {
            const ShotScore& x = scores[c][s];
            if (!x.present) return std::string("-");
            return fmt(x.psnr) + " / " + fmt(x.tpsnr) + " (" + fmt(x.tpsnrAboveNoise, 1) + ")" +
                   (x.framesPerSecond > 0 ? " @" + fmt(x.framesPerSecond) : "");
          },
          n == shots.size() ? fmt(p / double(n)) + " / " + fmt(t / double(n)) : "-");
    }
    double ft = 0, fp = 0;
    for (size_t s = 0; s < shots.size(); ++s) ft += floorT[s], fp += floorP[s];
    row(
        "noise floor", [&](size_t s) { return fmt(floorP[s]) + " / " + fmt(floorT[s]); },
        fmt(fp / double(shots.size())) + " / " + fmt(ft / double(shots.size())));
    if (!jsonPath.empty()) std::ofstream(jsonPath) << json.dump(2) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_score_shots: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
