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

// Sets near/far and rebuilds the projection's depth row in the OpenGL layout (NDC z -1 at near,
// +1 at far; far may be +infinity for a perspective camera, which an orthographic depth row
// cannot express: it is then built for far = 1e10, beyond which depth means "no surface" anyway).
void setClipPlanes(Camera& camera, double nearPlane, double farPlane);

// An inclusive pixel rectangle in EXR window coordinates (y down), as OpenEXR's Box2i.
struct PixelBox {
  int minX = 0, minY = 0, maxX = -1, maxY = -1;
  int width() const { return maxX - minX + 1; }
  int height() const { return maxY - minY + 1; }
  bool operator==(const PixelBox& o) const {
    return minX == o.minX && minY == o.minY && maxX == o.maxX && maxY == o.maxY;
  }
};

// The same camera with its image spread over `to` instead of `from` (both in one window
// coordinate system): the projection is shifted and scaled so that every world point lands on the
// same window pixel. A camera of the display window becomes the camera of an overscan or crop
// data window. Perspective and orthographic; near/far unchanged.
Camera reframeCamera(const Camera& camera, const PixelBox& from, const PixelBox& to);

// Camera-space point of pixel position (px, py) (pixels, y down, over the camera's width and
// height) at planar depth `depth`, for perspective and orthographic projections alike.
glm::dvec3 cameraPointAt(const glm::dmat4& inverseProjection, const Camera& camera, double px, double py,
                         double depth);

}  // namespace ssrcl
