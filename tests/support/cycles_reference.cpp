#include "support/cycles_reference.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <stdexcept>

#include "support/exr_fixtures.hpp"

namespace ssrcl::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

double lambda(const glm::dvec3& w, double alpha) {
  const double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

}  // namespace

// E(o) = integral of D G1(o) G1(l) / (4 o.z) over l = mean over visible-normal samples of G1(l),
// taken on a 128 x 128 grid of stratum midpoints (deterministic, converged to ~1e-4 here).
double directionalAlbedoSeparable(double cosO, double alpha) {
  const glm::dvec3 o(std::sqrt(std::max(0.0, 1.0 - cosO * cosO)), 0.0, cosO);
  const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * o.x, alpha * o.y, o.z));
  const glm::dvec3 t1 =
      vh.x * vh.x + vh.y * vh.y > 0 ? glm::normalize(glm::dvec3(-vh.y, vh.x, 0)) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t2 = glm::cross(vh, t1);
  const int n = 128;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double r = std::sqrt((i + 0.5) / n), phi = 2 * kPi * (j + 0.5) / n;
      const double s = 0.5 * (1 + vh.z);
      double p1 = r * std::cos(phi), p2 = r * std::sin(phi);
      p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * p2;
      const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2)) * vh;
      const glm::dvec3 h = glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)));
      const glm::dvec3 l = 2 * glm::dot(o, h) * h - o;
      if (l.z > 0) sum += 1 / (1 + lambda(l, alpha));
    }
  return sum / (n * n);
}

namespace {

// E on a grid of roughness (1/64 steps, alpha = roughness^2) and cos(theta_o) (1/256 steps),
// filled a roughness row at a time as pixels need it, read bilinearly: corpus frames hold tens of
// thousands of distinct (roughness, angle) pairs. The bundled samples' stripes lie on the grid.
class AlbedoTable {
 public:
  double operator()(double roughness, double cosO) {
    const double r = std::clamp(roughness, 0.0, 1.0) * kRoughSteps, c = std::clamp(cosO, 0.0, 1.0) * kCosSteps;
    const int r0 = std::min(int(r), kRoughSteps - 1), c0 = std::min(int(c), kCosSteps - 1);
    const double fr = r - r0, fc = c - c0;
    const std::vector<double>& a = row(r0);
    const std::vector<double>& b = row(r0 + 1);
    const double lo = a[c0] + fc * (a[c0 + 1] - a[c0]), hi = b[c0] + fc * (b[c0 + 1] - b[c0]);
    return lo + fr * (hi - lo);
  }

 private:
  static constexpr int kRoughSteps = 64, kCosSteps = 256;
  const std::vector<double>& row(int r) {
    std::vector<double>& values = rows_[r];
    if (values.empty()) {
      const double rough = double(r) / kRoughSteps;
      for (int c = 0; c <= kCosSteps; ++c)  // cos 0 is the grazing limit: nudge it inside
        values.push_back(directionalAlbedoSeparable(std::max(double(c) / kCosSteps, 1e-4), rough * rough));
    }
    return values;
  }
  std::map<int, std::vector<double>> rows_;
};

}  // namespace

CyclesReference loadCyclesReference(const std::string& exr, const std::string& cameraJson, double specular) {
  CyclesReference ref;
  GBufferSource source;
  source.file = exr;
  ref.gbuffer = loadGBuffer(source);
  const ExrContents passes = readExr(exr);
  auto channel = [&](const std::string& name) -> const std::vector<float>& {
    auto it = passes.channels.find("ViewLayer." + name);
    if (it == passes.channels.end()) throw std::runtime_error(exr + ": no channel ViewLayer." + name);
    return it->second.values;
  };
  std::filesystem::path p(exr);
  ref.camera = loadCameraJson(cameraJson.empty() ? (p.parent_path() / (p.stem().string() + ".camera.json")).string()
                                                 : cameraJson);
  const GBuffer& g = ref.gbuffer;
  const int w = g.depth.width, h = g.depth.height;
  const glm::dmat4 invViewProj = glm::inverse(ref.camera.projection * ref.camera.view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(ref.camera.view)[3]);
  const bool indexed = passes.channels.count("ViewLayer.IndexOB.X") > 0;
  const std::vector<float>& glossCol = channel("GlossCol.R");
  const std::vector<float>* index = indexed ? &channel("IndexOB.X") : nullptr;
  std::vector<const std::vector<float>*> gloss;
  for (const char* pass : {"GlossDir.", "GlossInd."})
    for (const char* c : {"R", "G", "B"}) gloss.push_back(&channel(std::string(pass) + c));

  static AlbedoTable albedo;  // shared by every render a program loads
  std::map<float, std::vector<size_t>> byRoughness;
  std::vector<double> values;
  for (int i = 0; i < w * h; ++i) {
    const glm::dvec3 n(g.normal.data[3 * i], g.normal.data[3 * i + 1], g.normal.data[3 * i + 2]);
    const bool surface = g.depth.data[i] < 1e9f && glm::length(n) > 0.5;
    const bool reflector = indexed ? (*index)[i] == 1.0f
                                   : n.z > 0.999 && g.roughness.data[i] < 0.9f && glossCol[i] > 0.999f;
    if (!surface || !reflector) continue;
    const int x = i % w, y = i / w;
    const glm::dvec4 q = invViewProj * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
    const glm::dvec3 toEye = glm::normalize(eye - glm::dvec3(q) / q.w);
    const float rough = std::clamp(g.roughness.data[i], 0.0f, 1.0f);
    if (!indexed) byRoughness[rough].push_back(ref.pixels.size());
    ref.pixels.push_back(i);
    ref.scale.push_back(specular * albedo(rough, glm::dot(glm::normalize(n), toEye)));
    for (int c = 0; c < 3; ++c) {
      ref.cycles.push_back((*gloss[c])[i] + (*gloss[3 + c])[i]);
      values.push_back(ref.cycles.back());
    }
  }
  if (values.empty()) throw std::runtime_error(exr + ": no reflector pixels");
  std::sort(values.begin(), values.end());
  ref.peak = values[std::min(values.size() - 1, size_t(0.999 * values.size()))];

  std::vector<size_t> all;
  for (size_t k = 0; k < ref.pixels.size(); ++k) all.push_back(k);
  if (!indexed) {
    // Stripes only: pixels on a boundary between two roughnesses hold blends.
    all.clear();
    for (auto& [rough, ks] : byRoughness)
      if (ks.size() > 1000) {
        ref.groups.push_back({"r=" + std::to_string(rough).substr(0, 6), ks});
        all.insert(all.end(), ks.begin(), ks.end());
      }
    std::sort(all.begin(), all.end());
  }
  ref.groups.insert(ref.groups.begin(), {"all", all});
  return ref;
}

ReferenceError referenceError(const CyclesReference& ref, const Image& reflection, const std::vector<size_t>& group) {
  double se = 0, seLow = 0, abs = 0, signedSum = 0;
  std::vector<double> perPixel;
  perPixel.reserve(group.size());
  for (size_t k : group) {
    const size_t i = size_t(ref.pixels[k]);
    double pixelSe = 0, pixelAbs = 0;
    for (int c = 0; c < 3; ++c) {
      const double ours = ref.scale[k] * reflection.data[reflection.channels * i + c];
      const double diff = ours - ref.cycles[3 * k + c];
      pixelSe += diff * diff;
      pixelAbs += std::abs(diff);
      signedSum += diff;
    }
    se += pixelSe;
    abs += pixelAbs;
    if (reflection.channels == 4 && reflection.data[4 * i + 3] < 0.5f) seLow += pixelSe;
    perPixel.push_back(pixelAbs / 3);
  }
  const double n = 3.0 * std::max<size_t>(group.size(), 1);
  ReferenceError e;
  e.rmse = std::sqrt(se / n);
  e.meanAbs = abs / n;
  e.bias = signedSum / n;
  e.psnr = 20 * std::log10(ref.peak / std::max(e.rmse, 1e-30));
  e.lowConfidence = se > 0 ? seLow / se : 0;
  if (!perPixel.empty()) {
    std::nth_element(perPixel.begin(), perPixel.begin() + perPixel.size() * 99 / 100, perPixel.end());
    e.p99 = perPixel[perPixel.size() * 99 / 100] / ref.peak;
  }
  return e;
}

}  // namespace ssrcl::test
