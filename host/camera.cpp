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

// Accepted layouts (row-major, camera looking down -Z, d = -z_camera the planar depth). Row 2 must
// be (0, 0, A, B): no x or y terms, so that NDC z is a function of depth alone.
//
// Perspective, last row (0, 0, -1, 0): NDC z = -A + B / d.
//   B < 0          NDC z grows with depth: OpenGL, -1 at near, +1 at far (A = -1: infinite far).
//                  A [0, 1]-depth (D3D, Vulkan) matrix of this kind reads as OpenGL and gets a near
//                  plane of about half its own (exactly near * far / (2 far - near)), its far exact.
//   B > 0, A < 1   reversed Z with [0, 1] depth (D3D, Vulkan, glClipControl): 1 at near, 0 at far
//                  (A = 0: infinite far).
//   B > 0, A >= 1  reversed OpenGL: 1 at near, -1 at far (A = 1: infinite far). A [0, 1] reversed
//                  matrix whose far is at most twice its near lands here too, with its far read
//                  larger than it is.
// Orthographic, last row (0, 0, 0, 1): NDC z = -A d + B.
//   A < 0          OpenGL, -1 at near, +1 at far.
//   A > 0          reversed, 1 at near, -1 at far; a [0, 1] reversed matrix (0 at far) gets a far
//                  plane of 2 far - near.
// Wherever the layout is ambiguous the reading errs on the safe side: the derived [near, far]
// always contains the true one, so no surface is lost; give "near" and "far" for exact values.
void deriveClipPlanes(const glm::dmat4& projection, double& nearPlane, double& farPlane) {
  const double a = at(projection, 2, 2);
  const double b = at(projection, 2, 3);
  const bool perspective = lastRowIs(projection, 0, 0, -1, 0);
  if (!perspective && !lastRowIs(projection, 0, 0, 0, 1)) {
    throw Error(ErrorCode::InvalidInput,
                "projection is neither a perspective (last row 0,0,-1,0) nor an orthographic (last row 0,0,0,1) "
                "matrix of a camera looking down -Z");
  }
  if (at(projection, 2, 0) != 0.0 || at(projection, 2, 1) != 0.0)
    throw Error(ErrorCode::InvalidInput, "projection's depth row (row 3) depends on x or y (an oblique near plane)");
  if (perspective) {
    if (b == 0.0 || !std::isfinite(a) || !std::isfinite(b))
      throw Error(ErrorCode::InvalidInput, "perspective projection has no depth range (row 3 is 0,0,A,0)");
    if (b < 0.0) {
      nearPlane = b / (a - 1.0);
      farPlane = a == -1.0 ? INFINITY : b / (a + 1.0);
    } else if (a < 1.0) {
      nearPlane = b / (a + 1.0);
      farPlane = a == 0.0 ? INFINITY : b / a;
    } else {
      nearPlane = b / (a + 1.0);
      farPlane = a == 1.0 ? INFINITY : b / (a - 1.0);
    }
  } else {
    if (a == 0.0 || !std::isfinite(a) || !std::isfinite(b))
      throw Error(ErrorCode::InvalidInput, "orthographic projection has no depth range");
    // NDC z = -a d + b; near and far are where it is -1 and +1 (standard) or +1 and -1 (reversed).
    const double sign = a < 0.0 ? 1.0 : -1.0;
    nearPlane = (b + sign) / a;
    farPlane = (b - sign) / a;
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
  // The kernels index pixels, and the HZB's texels (4/3 of the pixels), with 32-bit ints.
  constexpr long long kMaxPixels = 1LL << 30;
  if (static_cast<long long>(camera.width) * camera.height > kMaxPixels) {
    fail(what, std::to_string(camera.width) + "x" + std::to_string(camera.height) + " is " +
                   std::to_string(static_cast<long long>(camera.width) * camera.height) +
                   " pixels, more than the 1073741824 (2^30) a frame may have");
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
