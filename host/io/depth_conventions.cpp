// Depth passes as other renderers write them, turned into planar view depth.
#include <cmath>
#include <glm/glm.hpp>

#include "conventions.hpp"

namespace ssrcl::detail {

// A point at planar depth d on the pixel's ray is at distance d / (-dir.z) from the centre, with
// dir the ray's unit direction; an orthographic ray has dir.z = -1, so radial reads as planar.
float planarFromRadialAt(float radial, const glm::dmat4& inverse, const Camera& camera, int x, int y) {
  if (!isSurfaceDepth(radial)) return radial;
  const glm::dvec3 near = cameraPointAt(inverse, camera, x + 0.5, y + 0.5, 1.0);
  const glm::dvec3 far = cameraPointAt(inverse, camera, x + 0.5, y + 0.5, 2.0);
  return float(radial * -glm::normalize(far - near).z);
}

Image planarFromRadial(const Image& radial, const Camera& camera) {
  const glm::dmat4 inverse = glm::inverse(camera.projection);
  Image planar = radial;
  for (int y = 0; y < radial.height; ++y)
    for (int x = 0; x < radial.width; ++x) planar.at(x, y, 0) = planarFromRadialAt(radial.at(x, y, 0), inverse, camera, x, y);
  return planar;
}

Image planarFromPositions(const Image& positions, const Camera& camera) {
  Image planar(positions.width, positions.height, 1);
  for (int y = 0; y < positions.height; ++y)
    for (int x = 0; x < positions.width; ++x) {
      const glm::dvec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
      planar.at(x, y, 0) = !isSurfacePosition(p) ? 1e10f : float(-(camera.view * glm::dvec4(p, 1.0)).z);
    }
  return planar;
}

}  // namespace ssrcl::detail
