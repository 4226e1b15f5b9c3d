#pragma once
#include <string>

#include "scenes/analytic_scene.hpp"

namespace ssrcl::test {

// A rendered shot made up: frames <directory>/<prefix>.<frame, 4 digits>.exr (Blender multilayer
// naming, half colour, float data passes) with <prefix>.<frame>.camera.json sidecars, of an
// analytic scene seen by a camera orbiting it by `degreesPerFrame` and moving back from its target
// by `dollyPerFrame`.
struct AnalyticSequence {
  std::string directory;
  std::string prefix = "shot";
  std::string scene = "spheres_on_mirror";
  int firstFrame = 1001;
  int frameCount = 8;
  int width = 64, height = 36;
  double degreesPerFrame = 2.0;
  double dollyPerFrame = 0.0;  // world units along the line from the target to the eye
  double roughness = -1.0;  // >= 0: every surface this rough (the scenes are mirrors)
  double fovYDegrees = 0.0; // > 0: the camera's vertical field of view instead of the scene's
};

// Writes the frames; returns the pattern naming them ("<directory>/<prefix>.####.exr").
std::string writeAnalyticSequence(const AnalyticSequence& sequence);

// What the frames show: the scene (with the sequence's roughness) and frame `index`'s camera
// (0 for the first frame), in double precision, for truth computed from them.
Scene sequenceScene(const AnalyticSequence& sequence);
Camera sequenceCamera(const AnalyticSequence& sequence, int index);

}  // namespace ssrcl::test
