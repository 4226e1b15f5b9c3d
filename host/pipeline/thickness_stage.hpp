#pragma once
// Adaptive surface thickness (kernels/thickness.cl): each pixel's thickness from the visible extent
// of its surface along its row and column, applied to setup's surface planes. Runs only with
// ThicknessModel::Adaptive.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class ThicknessStage {
 public:
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, const TraceSettings& s, StageEvents& events);

 private:
  bool enabled_ = false;
  FrameShape frame_;
  cl::Kernel kernel_;
  cl::Buffer rowRuns_;  // per pixel: its row run's length and chord
};

}  // namespace ssrcl::detail
