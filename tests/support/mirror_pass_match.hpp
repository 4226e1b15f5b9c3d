#pragma once
// A written mirror reflection pass (an `ssrcl trace` or `ssrcl batch` output of an analytic frame,
// traced with --edge-fade 0) against the frame's exact reflections (scenes/analytic_scene.hpp).
#include <cstddef>
#include <string>

#include "scenes/analytic_scene.hpp"

namespace ssrcl::test {

struct MirrorPassMatch {
  std::size_t visible = 0, visibleOk = 0;  // reflected hits the camera sees; those matched
  std::size_t missed = 0, missedOk = 0;    // reflections of sky or off screen; those with A = 0
  double visibleRate() const { return visible ? double(visibleOk) / double(visible) : 0.0; }
  double missedRate() const { return missed ? double(missedOk) / double(missed) : 0.0; }
};

// Visible hits match with A = 1 and RGB within test_mirror_analytic's allowance (0.05 plus what one
// pixel of hit error costs there) plus half-float rounding; misses with A = 0. The output's
// channels are R, G, B, A (the default layer); its size must be the camera's.
MirrorPassMatch matchExactReflections(const std::string& output, const Scene& scene, const Camera& camera);

// Floor on both rates. Measured 0.9905 and 0.9932 (PoCL, a 160x90 frame of spheres_on_mirror);
// 1% margin for another platform's hit decisions.
inline constexpr double kMirrorPassFloor = 0.98;

}  // namespace ssrcl::test
