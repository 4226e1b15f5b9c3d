#include "support/cycles_reference.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>

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

CyclesFloorReference loadCyclesFloorReference(const std::string& exr, const std::string& cameraJson, double specular) {
  CyclesFloorReference ref;
  GBufferSource source;
  source.file = exr;
  ref.gbuffer = loadGBuffer(source);
  auto pass = [&](const std::string& name) {
    GBufferSource s = source;
    s.colorChannels = "ViewLayer." + name + ".R,ViewLayer." + name + ".G,ViewLayer." + name + ".B";
    s.constantRoughness = 0.0f;
    return loadGBuffer(s).color;
  };
  const Image glossDir = pass("GlossDir"), glossInd = pass("GlossInd"), glossCol = pass("GlossCol");
  std::filesystem::path p(exr);
  ref.camera = loadCameraJson(cameraJson.empty() ? (p.parent_path() / (p.stem().string() + ".camera.json")).string()
                                                 : cameraJson);
  const GBuffer& g = ref.gbuffer;
  const int w = g.depth.width, h = g.depth.height;
  const glm::dmat4 invViewProj = glm::inverse(ref.camera.projection * ref.camera.view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(ref.camera.view)[3]);

  // Floor: upward world normal (Blender is Z-up), a surface, glossy or mirror, and Cycles' glossy
  // colour 1 (0 or fractional on object edges).
  std::map<std::pair<float, int>, double> albedoCache;  // on (roughness, n.o in 1/512 steps)
  std::map<float, std::vector<size_t>> byRoughness;
  for (int i = 0; i < w * h; ++i) {
    if (!(g.normal.data[3 * i + 2] > 0.999f && g.depth.data[i] < 1e9f && g.roughness.data[i] < 0.9f &&
          glossCol.data[3 * i] > 0.999f))
      continue;
    const int x = i % w, y = i / w;
    const glm::dvec4 q = invViewProj * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
    const glm::dvec3 toEye = glm::normalize(eye - glm::dvec3(q) / q.w);
    const int bin = std::clamp(int(toEye.z * 512), 1, 512);  // n = +Z on the floor
    const float rough = g.roughness.data[i];
    auto it = albedoCache.find({rough, bin});
    if (it == albedoCache.end())
      it = albedoCache
               .emplace(std::make_pair(rough, bin),
                        directionalAlbedoSeparable((bin - 0.5) / 512.0, double(rough) * rough))
               .first;
    byRoughness[rough].push_back(ref.floor.size());
    ref.floor.push_back(i);
    ref.scale.push_back(specular * it->second);
    for (int c = 0; c < 3; ++c) {
      ref.cycles.push_back(glossDir.data[3 * i + c] + glossInd.data[3 * i + c]);
      ref.peak = std::max(ref.peak, ref.cycles.back());
    }
  }
  // Stripes only: pixels on a boundary between two roughnesses hold blends.
  std::vector<size_t> all;
  for (auto& [rough, ks] : byRoughness)
    if (ks.size() > 1000) {
      ref.groups.push_back({"r=" + std::to_string(rough).substr(0, 6), ks});
      all.insert(all.end(), ks.begin(), ks.end());
    }
  std::sort(all.begin(), all.end());
  ref.groups.insert(ref.groups.begin(), {"floor", all});
  return ref;
}

FloorError floorError(const CyclesFloorReference& ref, const Image& reflection, const std::vector<size_t>& group) {
  double se = 0, abs = 0;
  for (size_t k : group)
    for (int c = 0; c < 3; ++c) {
      const double ours = ref.scale[k] * reflection.data[4 * size_t(ref.floor[k]) + c];
      const double diff = ours - ref.cycles[3 * k + c];
      se += diff * diff;
      abs += std::abs(diff);
    }
  const double n = 3.0 * std::max<size_t>(group.size(), 1);
  return {std::sqrt(se / n), abs / n};
}

}  // namespace ssrcl::test
