// A camera's image moved to another pixel window (overscan, crop), and pixels unprojected to
// camera space: the geometry the loader needs to turn other renderers' passes into ours.
#include <glm/glm.hpp>

#include "ssrcl/camera.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {

// Pixel x of window `from` is x - from.minX over its width; the same pixel of `to` is
// x - to.minX over to's width. NDC is affine in both, so one affine map applied to clip space
// (x' = a x + b w) moves the whole image; GLM indexes m[column][row].
Camera reframeCamera(const Camera& camera, const PixelBox& from, const PixelBox& to) {
  if (from.width() <= 0 || from.height() <= 0 || to.width() <= 0 || to.height() <= 0)
    throw Error(ErrorCode::InvalidInput, "camera window is empty");
  const double sx = double(from.width()) / to.width(), sy = double(from.height()) / to.height();
  const double ox = from.minX - to.minX, oy = from.minY - to.minY;
  glm::dmat4 map(1.0);
  map[0][0] = sx;
  map[3][0] = sx - 1.0 + 2.0 * ox / to.width();
  map[1][1] = sy;
  map[3][1] = 1.0 - sy - 2.0 * oy / to.height();
  Camera out = camera;
  out.projection = map * camera.projection;
  out.width = to.width();
  out.height = to.height();
  return out;
}

// Two NDC depths that are finite for every accepted depth layout (standard, reversed, infinite
// far) give two points of the pixel's ray; the point at the planar depth lies on their line.
glm::dvec3 cameraPointAt(const glm::dmat4& inverseProjection, const Camera& camera, double px, double py,
                         double depth) {
  const double nx = 2.0 * px / camera.width - 1.0, ny = 1.0 - 2.0 * py / camera.height;
  const glm::dvec4 a = inverseProjection * glm::dvec4(nx, ny, 0.25, 1.0);
  const glm::dvec4 b = inverseProjection * glm::dvec4(nx, ny, 0.5, 1.0);
  const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
  const double t = (-depth - p0.z) / (p1.z - p0.z);
  return p0 + (p1 - p0) * t;
}

}  // namespace ssrcl
