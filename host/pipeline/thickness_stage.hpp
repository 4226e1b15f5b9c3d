#pragma once
// Surface thickness (kernels/thickness.cl), applied to setup's surface planes: the adaptive
// model's, from the visible extent of each pixel's surface along its row and column (with
// ThicknessModel::Adaptive), then the exact one where a back-face depth pass knows it.
#include "frame_resources.hpp"
#include "host_backed_buffer.hpp"

namespace ssrcl::detail {

class ThicknessStage {
 public:
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s, bool backDepth);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  // `backDepth`: the planar back-face depth (0: unknown), with backDepth configured, of a camera
  // that is `orthographic` or not.
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, const TraceSettings& s, const float* backDepth,
               bool orthographic, StageEvents& events);

 private:
  Device::Impl* device_ = nullptr;
  bool adaptive_ = false, backDepth_ = false;
  FrameShape frame_;
  cl::Kernel kernel_, known_;
  cl::Buffer rowRuns_;  // per pixel: its row run's length and chord
  HostInput back_;      // per pixel: the back-face depth
};

}  // namespace ssrcl::detail
