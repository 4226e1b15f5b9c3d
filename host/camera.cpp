#include "ssrcl/camera.hpp"

#include <cmath>
#include <glm/glm.hpp>
#include <sstream>
#include <string>

#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

// GLM is column-major: row r, column c of the usual (row-major) notation is m[c][r].
double at(const glm::dmat4& m, int row, int col) { return m[col][row]; }

bool lastRowIs(const glm::dmat4& m, double a, double b, double c, double d) {
  return at(m, 3, 0) == a && at(m, 3, 1) == b && at(m, 3, 2) == c && at(m, 3, 3) == d;
}

bool allFinite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// |det| relative to the product of the column lengths (Hadamard's bound), so the test does not
// depend on the scene's units. Columns, not rows: a view matrix far from the origin has long rows
// (the translation) but only one long column, and a perspective matrix scores ~0.7 for any clip range.
bool isSingular(const glm::dmat4& m) {
  double bound = 1.0;
  for (int c = 0; c < 4; ++c) bound *= glm::length(m[c]);
  return bound == 0.0 || std::abs(glm::determinant(m)) <= 1e-12 * bound;
}

[[noreturn]] void fail(const char* what, const std::string& problem) {
  throw Error(ErrorCode::InvalidInput, std::string(what) + ": " + problem);
}

}  // namespace

void deriveClipPlanes(const glm::dmat4& projection, double& nearPlane, double& farPlane) {
  const double p22 = at(projection, 2, 2);
  const double p23 = at(projection, 2, 3);
  if (lastRowIs(projection, 0, 0, -1, 0)) {
    // z_clip = p22*z + p23, w_clip = -z; NDC z = -1 at z = -near and +1 at z = -far.
    nearPlane = p23 / (p22 - 1.0);
    farPlane = p22 == -1.0 ? INFINITY : p23 / (p22 + 1.0);
  } else if (lastRowIs(projection, 0, 0, 0, 1)) {
    // z_ndc = p22*z + p23 is linear; solve for z = -near (NDC -1) and z = -far (NDC +1).
    if (p22 == 0.0) throw Error(ErrorCode::InvalidInput, "orthographic projection has no depth range");
    nearPlane = (p23 + 1.0) / p22;
    farPlane = (p23 - 1.0) / p22;
  } else {
    throw Error(ErrorCode::InvalidInput,
                "projection is neither OpenGL perspective (last row 0,0,-1,0) nor orthographic "
                "(last row 0,0,0,1)");
  }
}

void validateCamera(const Camera& camera, const char* what) {
  if (!allFinite(camera.view)) fail(what, "view matrix has a non-finite entry");
  if (!allFinite(camera.projection)) fail(what, "projection matrix has a non-finite entry");
  if (isSingular(camera.view)) fail(what, "view matrix is singular");
  if (isSingular(camera.projection)) fail(what, "projection matrix is singular");
  if (camera.width <= 0 || camera.height <= 0) {
    fail(what, "width and height must be positive (got " + std::to_string(camera.width) + "x" +
                   std::to_string(camera.height) + ")");
  }
  // Written so that NaN fails too; far may be +infinity.
  if (!(camera.nearPlane > 0.0 && std::isfinite(camera.nearPlane) && camera.farPlane > camera.nearPlane)) {
    std::ostringstream s;
    s.precision(17);
    s << "near and far must satisfy 0 < near < far (got near=" << camera.nearPlane << ", far=" << camera.farPlane
      << ")";
    fail(what, s.str());
  }
}

glm::dvec3 cameraToScreen(const Camera& camera, const glm::dvec3& cameraPoint) {
  const glm::dvec4 clip = camera.projection * glm::dvec4(cameraPoint, 1.0);
  const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  return {(ndc.x + 1.0) * 0.5 * camera.width, (1.0 - ndc.y) * 0.5 * camera.height, -cameraPoint.z};
}

}  // namespace ssrcl
