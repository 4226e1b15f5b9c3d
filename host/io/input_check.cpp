// The check before tracing: does the normal pass agree with the surface the depth describes,
// under the conventions the user declared? Shading normals differ from geometric ones on bumps
// and thin geometry, so the check compares conventions against each other over the whole frame
// and refuses only when another reading explains the passes clearly better, or none does.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "conventions.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

// Frames are sampled on a grid of at most this many pixels: the statistic is a frame mean.
constexpr long long kMaxSamples = 1LL << 14;
// A pixel filter blends positions across edges, but most pixels lie inside a surface, where a
// render's position is its pixel's own to a fraction of a pixel.
constexpr double kPositionPixelsOff = 1.0;
// Neighbours further apart in depth than this (relative) are across an edge, not one surface.
constexpr double kContinuity = 0.05;
// A reading is preferred over the declared one when, summed over the frame, the pass normals are
// closer to it by more than this share of how far apart the two readings put them (1: exactly
// at the other reading, 0: halfway, -1: exactly at the declared one). Per-pixel noise such as bump
// mapping moves a normal away from both readings alike, so it shrinks the score but not its sign.
constexpr double kPreferShare = 0.5;
// Readings this close (mean degrees apart) cannot be told apart, and give the same reflection.
constexpr double kMinSeparationDegrees = 1.0;
// When the best reading still disagrees this much, no convention explains the passes.
constexpr double kNothingFitsDegrees = 45.0;

struct Hypothesis {
  std::string depth, normals;
  const Image* planar;  // depth under this hypothesis
  NormalSpace space;
  int negatedAxis;  // -1 none, else the axis of the normal pass read with its sign flipped
};

// Depth-derived normals in eye space (0 where the pixel's surface cannot be told), on the grid.
std::vector<glm::dvec3> geometricNormals(const Image& planar, const Camera& camera, int stride) {
  const glm::dmat4 inverse = glm::inverse(camera.projection);
  const auto point = [&](int x, int y) {
    return cameraPointAt(inverse, camera, x + 0.5, y + 0.5, planar.at(x, y, 0));
  };
  // The neighbour on the side whose depth is closer, so a one-sided edge does not count.
  const auto tangent = [&](int x, int y, int dx, int dy, glm::dvec3& t) {
    const float d = planar.at(x, y, 0);
    const int ax = x - dx, ay = y - dy, bx = x + dx, by = y + dy;
    if (ax < 0 || ay < 0 || bx >= planar.width || by >= planar.height) return false;
    const float da = planar.at(ax, ay, 0), db = planar.at(bx, by, 0);
    if (!detail::isSurfaceDepth(da) || !detail::isSurfaceDepth(db)) return false;
    const bool useB = std::abs(db - d) <= std::abs(da - d);
    if (std::abs((useB ? db : da) - d) > kContinuity * d) return false;
    t = useB ? point(bx, by) - point(x, y) : point(x, y) - point(ax, ay);
    return true;
  };
  std::vector<glm::dvec3> normals;
  for (int y = stride / 2; y < planar.height; y += stride)
    for (int x = stride / 2; x < planar.width; x += stride) {
      glm::dvec3 n(0.0), tx, ty;
      if (detail::isSurfaceDepth(planar.at(x, y, 0)) && tangent(x, y, 1, 0, tx) && tangent(x, y, 0, 1, ty)) {
        n = glm::cross(tx, ty);
        const double length = glm::length(n);
        n = length > 0.0 && std::isfinite(length) ? n / length : glm::dvec3(0.0);
        if (glm::dot(n, point(x, y)) > 0.0) n = -n;  // the side the camera sees
      }
      normals.push_back(n);
    }
  return normals;
}

// The depth pass read as radial, in planar depth where geometricNormals reads it (the grid and
// each grid pixel's four neighbours): converting the whole frame took longer than the check.
Image radialOnGrid(const Image& radial, const Camera& camera, int stride) {
  const glm::dmat4 inverse = glm::inverse(camera.projection);
  Image planar = radial;
  const auto convert = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < radial.width && y < radial.height)
      planar.at(x, y, 0) = detail::planarFromRadialAt(radial.at(x, y, 0), inverse, camera, x, y);
  };
  for (int y = stride / 2; y < radial.height; y += stride)
    for (int x = stride / 2; x < radial.width; x += stride) {
      convert(x, y);
      convert(x - 1, y);
      convert(x + 1, y);
      convert(x, y - 1);
      convert(x, y + 1);
    }
  return planar;
}

std::string describe(const Hypothesis& h) { return h.depth + " depth, " + h.normals + " normals"; }

std::string decimal(double value) {
  char text[32];
  std::snprintf(text, sizeof text, value < 1.0 && value > -1.0 ? "%.2f" : "%.1f", value);
  return text;
}

}  // namespace

InputCheckReport checkInputConventions(const GBuffer& g, const GBufferSource& source, const Camera& camera) {
  const bool fromPositions = !source.positionChannels.empty();
  const Image& geometry = fromPositions ? g.position : g.depth;
  if (camera.width != geometry.width || camera.height != geometry.height)
    throw Error(ErrorCode::InvalidArgument, "checkInputConventions: camera and G-buffer sizes differ");

  // Positions and a depth pass in one file must give the same depth (read as planar or radial,
  // whichever fits): else the positions are not world space or the camera is not the render's.
  if (fromPositions && !g.depth.empty()) {
    const Image fromP = detail::planarFromPositions(g.position, camera);
    const Image radial = detail::planarFromRadial(g.depth, camera);
    std::vector<double> planarOff, radialOff;
    const int step = std::max<int>(1, int(g.depth.data.size() / kMaxSamples));
    for (std::size_t i = 0; i < g.depth.data.size(); i += step) {
      const double p = fromP.data[i], d = g.depth.data[i], r = radial.data[i];
      if (!(p > 0.0 && p < 1e9 && d > 0.0 && d < 1e9 && std::isfinite(r))) continue;
      planarOff.push_back(std::abs(p - d) / d);
      radialOff.push_back(std::abs(p - r) / r);
    }
    if (planarOff.size() >= 64) {
      const double planar = detail::median(planarOff), rad = detail::median(radialOff);
      if (std::min(planar, rad) > 0.01)
        throw Error(ErrorCode::InvalidInput,
                    (source.positionFile.empty() ? source.file : source.positionFile) +
                        ": the position pass disagrees with the depth pass (median depth difference " +
                        decimal(100 * planar) + "% read as planar depth, " + decimal(100 * rad) +
                        "% as radial): the positions are not in world space or the camera does not match the "
                        "render; check --position and --camera (or --no-input-check to trace anyway)");
    }
  }

  // Positions must land on their own pixels through the camera. A field of view, aspect or pose
  // that is not the render's moves them (a 10% wrong field of view by 10% of their distance from
  // the centre) where the depth-derived normals below barely turn (1-2 degrees on average).
  if (fromPositions) {
    std::vector<double> off;
    const Image& p = g.position;
    const int step = std::max<int>(1, int((long long)p.width * p.height / kMaxSamples));
    for (long long i = 0; i < (long long)p.width * p.height; i += step) {
      const int x = int(i % p.width), y = int(i / p.width);
      const glm::dvec3 world(p.at(x, y, 0), p.at(x, y, 1), p.at(x, y, 2));
      if (!detail::isSurfacePosition(world)) continue;
      const glm::dvec3 eye(camera.view * glm::dvec4(world, 1.0));
      const glm::dvec3 screen = cameraToScreen(camera, eye);
      const double d = glm::length(glm::dvec2(screen) - glm::dvec2(x + 0.5, y + 0.5));
      off.push_back(std::isfinite(d) && screen.z > 0.0 ? d : INFINITY);  // behind the camera: off
    }
    if (off.size() >= 64) {
      const double median = detail::median(off);
      if (!(median <= kPositionPixelsOff))
        throw Error(ErrorCode::InvalidInput,
                    (source.positionFile.empty() ? source.file : source.positionFile) +
                        ": the position pass does not land on its pixels through the camera (median " +
                        decimal(median) + " pixels off): the camera (field of view, aspect or pose) is not the "
                        "render's; check --camera or --fov (or --no-input-check to trace anyway)");
    }
  }

  const long long pixels = static_cast<long long>(geometry.width) * geometry.height;
  const int stride = std::max(1, int(std::ceil(std::sqrt(double(pixels) / kMaxSamples))));

  // Depth readings: the pass as planar and as radial (positions have one reading).
  // The pass itself is read where it is (no copy of a full-size image); the reading derived from it here.
  Image derived;
  std::vector<std::pair<std::string, const Image*>> depths;
  if (fromPositions) {
    derived = detail::planarFromPositions(g.position, camera);
    depths.emplace_back("position", &derived);
  } else {
    derived = radialOnGrid(g.depth, camera, stride);
    depths.emplace_back("planar", &g.depth);
    depths.emplace_back("radial", &derived);
  }
  const std::string declaredDepth = fromPositions ? "position" : depthKindName(source.depthKind);

  std::vector<Hypothesis> hypotheses;
  for (const auto& [name, planar] : depths) {
    for (NormalSpace space : {NormalSpace::World, NormalSpace::Camera, NormalSpace::CameraGL, NormalSpace::CameraCV})
      hypotheses.push_back({name, normalSpaceName(space), planar, space, -1});
    // The declared space with one axis flipped: a pass no option converts.
    for (int axis = 0; axis < 3; ++axis)
      hypotheses.push_back({name, std::string(normalSpaceName(source.normalSpace)) + " with " + "xyz"[axis] +
                                      " negated",
                            planar, source.normalSpace, axis});
  }

  const glm::dmat3 worldToEye(camera.view);
  std::vector<std::vector<glm::dvec3>> geometric;
  for (const auto& depth : depths) geometric.push_back(geometricNormals(*depth.second, camera, stride));

  // Per sample and hypothesis: the pass normal in eye space (0 if unusable) and the depth-derived one.
  const auto passNormal = [&](const Hypothesis& hyp, int x, int y) {
    glm::dvec3 n(g.normal.at(x, y, 0), g.normal.at(x, y, 1), g.normal.at(x, y, 2));
    if (hyp.negatedAxis >= 0) n[hyp.negatedAxis] = -n[hyp.negatedAxis];
    n = detail::normalToEye(n, hyp.space, worldToEye);
    const double length = glm::length(n);
    return length > 0.0 && std::isfinite(length) ? n / length : glm::dvec3(0.0);
  };
  const auto angle = [](const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * 180.0 / M_PI;
  };
  const auto geometricOf = [&](const Hypothesis& hyp) -> const std::vector<glm::dvec3>& {
    return geometric[hyp.planar == depths[0].second ? 0 : 1];
  };

  size_t declared = 0;
  for (size_t h = 0; h < hypotheses.size(); ++h)
    if (hypotheses[h].depth == declaredDepth && hypotheses[h].negatedAxis < 0 &&
        hypotheses[h].space == source.normalSpace)
      declared = h;

  // The declared reading per sample: its pass normal and their angle to its depth normal.
  const std::vector<glm::dvec3>& geoDeclared = geometricOf(hypotheses[declared]);
  std::vector<glm::dvec3> nDeclared;
  std::vector<double> aDeclared;
  for (int y = stride / 2; y < geometry.height; y += stride)
    for (int x = stride / 2; x < geometry.width; x += stride) {
      nDeclared.push_back(passNormal(hypotheses[declared], x, y));
      aDeclared.push_back(angle(nDeclared.back(), geoDeclared[aDeclared.size()]));
    }

  // Mean angle of each hypothesis, and its score against the declared one (see kPreferShare).
  std::vector<double> meanAngle(hypotheses.size(), 180.0), score(hypotheses.size(), 0.0),
      separation(hypotheses.size(), 0.0);
  long long declaredCount = 0;
  for (size_t h = 0; h < hypotheses.size(); ++h) {
    const std::vector<glm::dvec3>& geo = geometricOf(hypotheses[h]);
    const bool sameDepth = &geo == &geoDeclared;
    double sum = 0.0, gain = 0.0, apart = 0.0;
    long long count = 0, paired = 0;
    size_t i = 0;
    for (int y = stride / 2; y < geometry.height; y += stride)
      for (int x = stride / 2; x < geometry.width; x += stride, ++i) {
        if (geo[i] == glm::dvec3(0.0)) continue;
        const glm::dvec3 n = h == declared ? nDeclared[i] : passNormal(hypotheses[h], x, y);
        if (n == glm::dvec3(0.0)) continue;
        const double a = h == declared ? aDeclared[i] : angle(n, geo[i]);
        sum += a;
        ++count;
        if (h == declared || geoDeclared[i] == glm::dvec3(0.0)) continue;
        gain += aDeclared[i] - a;
        apart += angle(nDeclared[i], n) + (sameDepth ? 0.0 : angle(geoDeclared[i], geo[i]));
        ++paired;
      }
    if (count) meanAngle[h] = sum / count;
    if (apart > 0.0) score[h] = gain / apart;
    if (paired) separation[h] = apart / paired;
    if (h == declared) declaredCount = count;
  }

  size_t best = 0, preferred = declared;
  for (size_t h = 0; h < hypotheses.size(); ++h) {
    if (meanAngle[h] < meanAngle[best]) best = h;
    if (h != declared && separation[h] > kMinSeparationDegrees && score[h] > kPreferShare &&
        (preferred == declared || score[h] > score[preferred]))
      preferred = h;
  }
  InputCheckReport report;
  report.declared = {hypotheses[declared].depth, hypotheses[declared].normals, meanAngle[declared], 0.0};
  report.best = {hypotheses[best].depth, hypotheses[best].normals, meanAngle[best], score[best]};
  report.preferred = {hypotheses[preferred].depth, hypotheses[preferred].normals, meanAngle[preferred],
                      score[preferred]};
  for (size_t h = 0; h < hypotheses.size(); ++h)
    report.readings.push_back({hypotheses[h].depth, hypotheses[h].normals, meanAngle[h], score[h]});
  report.comparedPixels = declaredCount;
  // Too few usable pixels to judge (a frame of sky, a single flat card seen edge-on): no verdict.
  if (declaredCount < 64) return report;

  const std::string depthFile = (fromPositions ? source.positionFile : source.depthFile).empty()
                                    ? source.file
                                    : (fromPositions ? source.positionFile : source.depthFile);
  const std::string normalFile = source.normalFile.empty() ? source.file : source.normalFile;
  const std::string skip = " (or --no-input-check to trace anyway)";
  const std::string fits = "normals derived from the depth differ from the normal pass by " +
                           decimal(meanAngle[declared]) + " degrees on average as declared (" +
                           describe(hypotheses[declared]) + "), " + decimal(meanAngle[preferred]) + " as " +
                           describe(hypotheses[preferred]) + " (score " + decimal(score[preferred]) + " of 1)";
  if (preferred != declared) {
    const Hypothesis& b = hypotheses[preferred];
    if (b.negatedAxis >= 0)
      throw Error(ErrorCode::InvalidInput, normalFile + ": the normal pass's " + "xyz"[b.negatedAxis] +
                                               " axis appears flipped: " + fits +
                                               "; no option converts it, fix the pass" + skip);
    std::string options;
    if (b.depth != declaredDepth) options += "--depth-kind " + b.depth;
    if (b.space != source.normalSpace)
      options += (options.empty() ? "" : " and ") + std::string("--normal-space ") + normalSpaceName(b.space);
    const std::string what = b.depth != declaredDepth && b.space != source.normalSpace
                                 ? depthFile + ": the depth pass is " + b.depth + " and the normal pass is in " +
                                       b.normals + " space"
                             : b.depth != declaredDepth ? depthFile + ": the depth pass is " + b.depth + " depth, not " +
                                                              declaredDepth
                                                        : normalFile + ": the normal pass is in " + b.normals +
                                                              " space, not " + normalSpaceName(source.normalSpace);
    throw Error(ErrorCode::InvalidInput, what + ": " + fits + "; use " + options + skip);
  }
  if (meanAngle[best] > kNothingFitsDegrees)
    throw Error(ErrorCode::InvalidInput,
                depthFile + ": the depth and normal passes disagree under every convention (best " +
                    decimal(meanAngle[best]) + " degrees, as " + describe(hypotheses[best]) +
                    "): the camera probably does not match the render; check --camera or the header camera" + skip);
  return report;
}

}  // namespace ssrcl
