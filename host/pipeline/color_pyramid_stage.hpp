#pragma once
// The colour pyramid (kernels/color_pyramid.cl) for prefiltered hits. Setup writes level 0, which
// every hit reads. With TraceSettings::prefilter, after each traced batch the pyramid is weighted
// by where that batch's hits landed, reduced, and the rough hits read their footprint's mean from
// it (kernels/hit_prefilter.cl).
#include "hzb_stage.hpp"

namespace ssrcl::detail {

class SetupStage;
class TraceStage;

class ColorPyramidStage {
 public:
  // hitCounts false: a pyramid read at once with setup's weights (an auxiliary view's), which
  // needs neither the hit counts nor the kernels that weight and look up by them.
  void configure(Device::Impl& device, const TraceSettings& s, bool hitCounts = true);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const HzbStage& hzb, const SetupStage& setup, const TraceStage& trace);
  // A pyramid read at once, with the weights setup wrote (an auxiliary view's: no hit counts).
  void bind(const HzbStage& hzb);
  void reduce(cl::CommandQueue& q, StageEvents& events);
  // Clears the hit counts before the first batch.
  void enqueue(cl::CommandQueue& q, StageEvents& events);
  // After a batch (the trace's own parameters): counts its hits, reduces, looks the hits up.
  void prefilterHits(cl::CommandQueue& q, const TraceParams& params, StageEvents& events);

  cl::Buffer pyramid;  // (rgb * hits, hits) per texel, levels as the HZB's; level 0 (rgb, hits)

 private:
  bool reduce_ = false, hitCounts_ = true;
  FrameShape frame_;
  cl::Kernel reduce_kernel_, count_, weights_, lookup_;
  cl::Buffer counts_;
};

}  // namespace ssrcl::detail
