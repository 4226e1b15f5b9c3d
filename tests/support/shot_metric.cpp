#include "support/shot_metric.hpp"

#include <cmath>
#include <glm/glm.hpp>
#include <stdexcept>

#include "support/exr_fixtures.hpp"

namespace ssrcl::test {
namespace {

// Tangent plane and normal tests for "the same surface point": 1% of depth, 37 degrees (normal
// maps differ a little between neighbouring pixels).
constexpr double kPlaneTolerance = 0.01, kNormalCosine = 0.8;

struct Geometry {
  const CyclesReference& ref;
  glm::dmat4 inverseProjection, inverseView;
  std::vector<int> reflectorIndex;  // per pixel: its index in ref.pixels, -1 off the reflector

  explicit Geometry(const CyclesReference& r)
      : ref(r),
        inverseProjection(glm::inverse(r.camera.projection)),
        inverseView(glm::inverse(r.camera.view)),
        reflectorIndex(size_t(r.gbuffer.depth.width) * r.gbuffer.depth.height, -1) {
    for (size_t k = 0; k < r.pixels.size(); ++k) reflectorIndex[size_t(r.pixels[k])] = int(k);
  }
  int width() const { return ref.gbuffer.depth.width; }
  glm::dvec3 point(int i) const {
    const int x = i % width(), y = i / width();
    const glm::dvec3 c =
        cameraPointAt(inverseProjection, ref.camera, x + 0.5, y + 0.5, ref.gbuffer.depth.data[size_t(i)]);
    return glm::dvec3(inverseView * glm::dvec4(c, 1.0));
  }
  glm::dvec3 normal(int i) const {
    const float* n = &ref.gbuffer.normal.data[3 * size_t(i)];
    return glm::normalize(glm::dvec3(n[0], n[1], n[2]));
  }
};

}  // namespace

TemporalError temporalError(const CyclesReference& prev, const Image& passPrev, const CyclesReference& cur,
                            const Image& passCur, std::vector<double>* perPixel) {
  const Geometry gp(prev), gc(cur);
  const int w = prev.gbuffer.depth.width, h = prev.gbuffer.depth.height;
  if (perPixel) perPixel->assign(size_t(cur.gbuffer.depth.width) * cur.gbuffer.depth.height, NAN);
  double se = 0;
  TemporalError out;
  for (size_t k = 0; k < cur.pixels.size(); ++k) {
    const int i = cur.pixels[k];
    const glm::dvec3 p = gc.point(i);
    const glm::dvec3 s = cameraToScreen(prev.camera, glm::dvec3(prev.camera.view * glm::dvec4(p, 1.0)));
    if (!(s.z > 0.0) || !(s.x >= 0.0 && s.x < w && s.y >= 0.0 && s.y < h)) continue;
    const int j = int(s.y) * w + int(s.x);
    const int kp = gp.reflectorIndex[size_t(j)];
    if (kp < 0) continue;
    const glm::dvec3 nq = gp.normal(j);
    if (glm::dot(gc.normal(i), nq) < kNormalCosine) continue;
    if (std::abs(glm::dot(gp.point(j) - p, nq)) > kPlaneTolerance * s.z) continue;
    double pixel = 0;
    for (int c = 0; c < 3; ++c) {
      const double ec = passCur.data[size_t(passCur.channels) * size_t(i) + size_t(c)] - cur.cycles[3 * k + size_t(c)];
      const double ep =
          passPrev.data[size_t(passPrev.channels) * size_t(j) + size_t(c)] - prev.cycles[3 * size_t(kp) + size_t(c)];
      pixel += (ec - ep) * (ec - ep);
    }
    se += pixel;
    if (perPixel) (*perPixel)[size_t(i)] = pixel;
    ++out.pixels;
  }
  if (!out.pixels) throw std::runtime_error("temporalError: no reflector pixel of a frame is seen in the one before");
  out.te = std::sqrt(se / (3.0 * double(out.pixels)));
  out.tpsnr = 20.0 * std::log10(cur.peak / out.te);
  return out;
}

TemporalError noiseFloor(const CyclesReference& a, const CyclesReference& b) {
  // Over the pixels both renders call reflector: object-index edges differ with the seed.
  const Geometry gb(b);
  double se = 0;
  TemporalError out;
  for (size_t k = 0; k < a.pixels.size(); ++k) {
    const int kb = gb.reflectorIndex[size_t(a.pixels[k])];
    if (kb < 0) continue;
    for (size_t c = 0; c < 3; ++c) se += std::pow(a.cycles[3 * k + c] - b.cycles[3 * size_t(kb) + c], 2);
    ++out.pixels;
  }
  if (!out.pixels) throw std::runtime_error("noiseFloor: the two renders share no reflector pixel");
  out.te = std::sqrt(se / (3.0 * double(out.pixels)));
  out.tpsnr = 20.0 * std::log10(a.peak / out.te);
  return out;
}

Image readReflectionPass(const std::string& path) {
  const ExrContents exr = readExr(path);
  Image pass(exr.width, exr.height, 4);
  const char* rgba[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    const auto it = exr.channels.find(rgba[c]);
    if (it == exr.channels.end()) throw std::runtime_error(path + ": no channel " + rgba[c]);
    for (size_t i = 0; i < it->second.values.size(); ++i) pass.data[4 * i + size_t(c)] = it->second.values[i];
  }
  return pass;
}

}  // namespace ssrcl::test
