#pragma once
// The colour pyramid (kernels/color_pyramid.cl) for prefiltered hits. Setup writes level 0, which
// every hit reads. With TraceSettings::prefilter, after each traced batch the pyramid is weighted
// by where that batch's hits landed, reduced, and the rough hits read their footprint's mean from
// it (kernels/hit_prefilter.cl).
#include "hzb_stage.hpp"

namespace ssrcl::detail {

class ColorPyramidStage {
 public:
  // hitCounts false: a pyramid read at once with setup's weights (an auxiliary view's), which
  // needs neither the hit counts nor the kernels that weight and look up by them.
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s, bool hitCounts = true);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  void reduce(cl::CommandQueue& q, StageEvents& events);
  // Clears the hit counts before the first batch.
  void enqueue(cl::CommandQueue& q, StageEvents& events);
  // After a batch (the trace's own parameters): counts its hits, reduces, looks the hits up.
  void prefilterHits(cl::CommandQueue& q, const TraceParams& params, StageEvents& events);

 private:
  bool reduce_ = false, hitCounts_ = true;
  FrameShape frame_;
  cl::Kernel reduce_kernel_, count_, weights_, lookup_;
  cl::Buffer counts_;
};

}  // namespace ssrcl::detail
