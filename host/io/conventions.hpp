#pragma once
// Per-pass convention conversions, shared by applyInputConventions and the input check.
#include <algorithm>
#include <cmath>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// Depth values that mean a surface: finite, positive, below Cycles' 1e10 background.
inline bool isSurfaceDepth(float depth) { return depth > 0.0f && depth < 1e10f; }
// World positions that mean a surface: finite and not (0,0,0), which renderers write where there is none.
inline bool isSurfacePosition(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p != glm::dvec3(0.0);
}
// The median (upper, for an even count) of a non-empty sample.
inline double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
// A perspective projection's last row is 0,0,-1,0 (OpenGL layout); an orthographic one's 0,0,0,1.
inline bool isPerspective(const Camera& camera) { return camera.projection[2][3] != 0.0; }

// Planar depth from distances along each pixel's ray; values that mean no surface are kept.
Image planarFromRadial(const Image& radial, const Camera& camera);
// planarFromRadial at pixel (x, y) of distance `radial`; `inverse` is the inverse projection.
float planarFromRadialAt(float radial, const glm::dmat4& inverse, const Camera& camera, int x, int y);
// Planar depth from world positions; (0,0,0) and non-finite positions become 1e10 (no surface).
Image planarFromPositions(const Image& positions, const Camera& camera);

// A normal of `space` in OpenGL eye space (x right, y up, -z forward), the check's common ground.
glm::dvec3 normalToEye(const glm::dvec3& normal, NormalSpace space, const glm::dmat3& worldToEye);
// Normals of `space` turned into world space, in place; zero and non-finite normals stay what they are.
void toWorldNormals(Image& normals, NormalSpace space, const Camera& camera);

}  // namespace ssrcl::detail
