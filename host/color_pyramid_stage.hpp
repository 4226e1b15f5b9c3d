#pragma once
// The colour pyramid (kernels/color_pyramid.cl) for prefiltered hits. Setup writes level 0, which
// every hit reads; the coarser levels exist and are reduced only when TraceSettings::prefilter
// has rough hits read them.
#include "hzb_stage.hpp"

namespace ssrcl::detail {

class ColorPyramidStage {
 public:
  void configure(Device::Impl& device, const TraceSettings& s);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const HzbStage& hzb);
  void enqueue(cl::CommandQueue& q, StageEvents& events);

  cl::Buffer pyramid;  // (rgb * coverage, coverage) per texel, levels as the HZB's

 private:
  bool reduce_ = false;
  FrameShape frame_;
  cl::Kernel kernel_;
};

}  // namespace ssrcl::detail
