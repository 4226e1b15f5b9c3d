#pragma once
// The optional edge-aware filter (kernels/filter.cl) after the resolve, on the listed tiles.
// With it on, the resolve writes to this stage's input buffers instead of the outputs.
#include "setup_stage.hpp"

namespace ssrcl::detail {

class FilterStage {
 public:
  void configure(Device::Impl& device, const TraceSettings& s);
  bool enabled() const { return enabled_; }
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const SetupStage& setup, const cl::Buffer& rgba, const cl::Buffer& distance);
  void enqueue(cl::CommandQueue& q, const TraceSettings& s, int tiles, StageEvents& events);

  cl::Buffer resolvedRgba, resolvedDistance;  // its input

 private:
  bool enabled_ = false;
  FrameShape frame_;
  cl::Kernel kernel_;
};

}  // namespace ssrcl::detail
