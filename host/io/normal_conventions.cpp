// Normal passes in camera spaces, turned into world space.
#include <glm/glm.hpp>

#include "conventions.hpp"

namespace ssrcl::detail {

// OpenEXR/RenderMan camera space differs from OpenGL's eye space by the sign of z alone, OpenCV's
// by the signs of y and z (a half turn about x).
glm::dvec3 normalToEye(const glm::dvec3& normal, NormalSpace space, const glm::dmat3& worldToEye) {
  switch (space) {
    case NormalSpace::World:
      return worldToEye * normal;
    case NormalSpace::Camera:
      return {normal.x, normal.y, -normal.z};
    case NormalSpace::CameraGL:
      return normal;
    case NormalSpace::CameraCV:
      return {normal.x, -normal.y, -normal.z};
  }
  return normal;
}

// Normals go from eye to world by the inverse transpose of eye-to-world, i.e. the transpose of
// the view's linear part: exact for a view with scale or shear too. In place: world-space passes
// (Blender's) are left as read, with no copy of the frame's largest input.
void toWorldNormals(Image& normals, NormalSpace space, const Camera& camera) {
  if (space == NormalSpace::World) return;
  const glm::dmat3 eyeToWorld = glm::transpose(glm::dmat3(camera.view));
  for (int y = 0; y < normals.height; ++y)
    for (int x = 0; x < normals.width; ++x) {
      const glm::dvec3 n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
      const glm::dvec3 w = eyeToWorld * normalToEye(n, space, glm::dmat3(1.0));
      for (int c = 0; c < 3; ++c) normals.at(x, y, c) = float(w[c]);
    }
}

}  // namespace ssrcl::detail
