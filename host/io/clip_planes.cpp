// Clip planes for cameras whose file does not give them (OpenEXR's header matrices discard z),
// and the check of those a file does give.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "conventions.hpp"
#include "ssrcl/camera.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {

namespace {

// The nearest and farthest surface of a planar depth pass (INFINITY and 0 without any).
struct SurfaceRange {
  float nearest = INFINITY, farthest = 0.0f;
};

SurfaceRange surfaceRange(const Image& planarDepth) {
  SurfaceRange r;
  for (float d : planarDepth.data)
    if (detail::isSurfaceDepth(d)) r.nearest = std::min(r.nearest, d), r.farthest = std::max(r.farthest, d);
  return r;
}

}  // namespace

void setClipPlanes(Camera& camera, double n, double f) {
  const bool perspective = detail::isPerspective(camera);
  camera.nearPlane = n;
  camera.farPlane = f;
  const double rowFar = perspective || std::isfinite(f) ? f : 1e10;
  glm::dmat4& p = camera.projection;
  p[0][2] = p[1][2] = 0.0;
  if (perspective) {
    p[2][2] = std::isinf(rowFar) ? -1.0 : -(rowFar + n) / (rowFar - n);
    p[3][2] = std::isinf(rowFar) ? -2.0 * n : -2.0 * rowFar * n / (rowFar - n);
  } else {
    p[2][2] = -2.0 / (rowFar - n);
    p[3][2] = -(rowFar + n) / (rowFar - n);
  }
}

// Near: half the nearest surface, so no surface is clipped and rays are clipped well before the
// camera. Far: infinity, but for an orthographic camera, whose depth row has no infinite form
// (a far plane of 1e10 squeezes every depth into float rounding), twice the farthest surface.
void fitClipPlanes(Camera& camera, const Image& planarDepth) {
  const SurfaceRange r = surfaceRange(planarDepth);
  const double n = std::isfinite(r.nearest) ? 0.5 * r.nearest : 1.0;
  setClipPlanes(camera, n, detail::isPerspective(camera) ? INFINITY : 2.0 * std::max(double(r.farthest), n));
}

// Every surface must lie between the planes (a renderer clips what does not); 0.1% of slack
// for depth converted from radial distances or positions in float.
void checkClipPlanes(const Camera& camera, const Image& planarDepth, const std::string& cameraName) {
  const auto [nearest, farthest] = surfaceRange(planarDepth);
  const bool inside = nearest >= camera.nearPlane * (1.0 - 1e-3) && farthest <= camera.farPlane * (1.0 + 1e-3);
  if (inside || !std::isfinite(nearest)) return;
  std::ostringstream m;
  m << cameraName << ": its clip planes (" << camera.nearPlane << " to " << camera.farPlane
    << ") do not hold the depth pass's surfaces (" << nearest << " to " << farthest
    << "): the header is not this render's camera; give --camera";
  throw Error(ErrorCode::InvalidInput, m.str());
}

}  // namespace ssrcl
