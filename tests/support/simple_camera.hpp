#pragma once
#include <glm/gtc/matrix_transform.hpp>

#include "ssrcl/camera.hpp"

namespace ssrcl::test {

// A perspective camera at `eye` looking at `target` (+Y up), GL projection with the given
// vertical field of view in degrees.
inline Camera perspectiveCamera(int width, int height, glm::dvec3 eye = {0, 2, 5}, glm::dvec3 target = {0, 0, 0},
                                double fovYDegrees = 50.0, double nearPlane = 0.1, double farPlane = 100.0) {
  Camera c;
  c.width = width;
  c.height = height;
  c.view = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
  c.projection = glm::perspective(glm::radians(fovYDegrees), double(width) / height, nearPlane, farPlane);
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

}  // namespace ssrcl::test
