#pragma once
// An analytic scene rendered as the pipeline's inputs and run, for tests that drive the public API.
#include <string>

#include "ssrcl/camera.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::test {

struct AnalyticFrame {
  Camera camera;
  GBuffer g;
};

// Scene `name` (scenes/analytic_scene.hpp) at width x height from its preset view, the eye moved by
// `eyeShiftX` along world +X (so consecutive frames of a sequence differ).
AnalyticFrame renderAnalyticFrame(const std::string& name, int width, int height, double eyeShiftX = 0.0);

// The frame's images and camera set on `pipeline` with `settings`, committed and executed once.
void runFrame(Pipeline& pipeline, const AnalyticFrame& frame, const TraceSettings& settings);

}  // namespace ssrcl::test
