#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace ssrcl {

// A pinhole (or orthographic) camera as renderers describe it.
// Conventions (column-vector math, p' = M * p):
//   view       world -> camera; the camera looks down -Z, +Y up, +X right.
//   projection camera -> OpenGL clip space; NDC x,y,z in [-1, 1]; NDC y = +1 is the top row.
//   Pixel (x, y) covers [x, x+1) x [y, y+1) with y = 0 the top row, as EXR stores it.
//   Depth in the G-buffer is planar view depth: -z_camera (positive in front of the camera).
struct Camera {
  glm::dmat4 view{1.0};
  glm::dmat4 projection{1.0};
  int width = 0;
  int height = 0;
  double nearPlane = 0.0;  // positive planar distances; derived from projection when not given
  double farPlane = 0.0;   // may be +infinity
};

// Near/far of an OpenGL-style perspective or orthographic projection; throws Error(InvalidInput)
// when the matrix is neither.
void deriveClipPlanes(const glm::dmat4& projection, double& nearPlane, double& farPlane);

// Throws Error(InvalidInput) naming `what` when the camera cannot be used (singular matrices,
// non-positive size, near >= far).
void validateCamera(const Camera& camera, const char* what);

// Screen position in pixels (x right, y down) and planar depth of a camera-space point.
glm::dvec3 cameraToScreen(const Camera& camera, const glm::dvec3& cameraPoint);

}  // namespace ssrcl
