#pragma once
// The library's own stages before the trace (setup, HZB, adaptive thickness, range pyramid,
// colour pyramid), run on one frame through its internals with each stage timed apart by OpenCL
// profiling events, their outputs read back: the OpenCL side of bench/native_frame_stages. (The
// pipeline's stage times put the range pyramid under "hzb" and the colour pyramid under
// "color_mips" with the hits' prefilter.) Links ssrcl_internal.
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "native_frame_stages.hpp"
#include "ssrcl/camera.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::bench {

class DeviceFrameStages {
 public:
  // settings: thicknessModel Adaptive for the thickness stage (Constant: no thickness stage, 0 ms);
  // prefilter on (the colour pyramid). `gbuffer` must outlive this; `device` need not.
  DeviceFrameStages(const Device& device, const GBuffer& gbuffer, const Camera& camera, const TraceSettings& settings);
  ~DeviceFrameStages();
  DeviceFrameStages(const DeviceFrameStages&) = delete;
  DeviceFrameStages& operator=(const DeviceFrameStages&) = delete;

  // One run of the stages, waited for: each stage's device time.
  FrameStageMs run();
  // After run(), read back: the HZB, the surface planes, the range and colour pyramids.
  std::vector<float> hzb() const;
  std::vector<glm::vec4> planes() const;
  std::vector<glm::vec2> rangePyramid() const;
  std::vector<glm::vec4> colorPyramid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssrcl::bench
