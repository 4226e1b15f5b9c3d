#include "thickness_stage.hpp"

namespace ssrcl::detail {

const StageAccess ThicknessStage::access{"thickness", {Role::Positions}, {Role::Planes}};

void ThicknessStage::configure(Device::Impl& device, const TraceSettings& s) {
  enabled_ = s.thicknessModel == ThicknessModel::Adaptive;
  if (enabled_)
    kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "surface_plane.cl", "thickness.cl"}),
                         "surface_thickness");
}

void ThicknessStage::plan(DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  buffers.add(rowRuns_, enabled_ ? frame.pixels() * sizeof(cl_float2) : 0);
}

void ThicknessStage::bind(const FrameResources& resources) {
  if (enabled_)
    bindArgs(kernel_, 1, "positions, row, planes", resources.read(access, Role::Positions), rowRuns_,
             resources.write(access, Role::Planes));
}

void ThicknessStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, const TraceSettings& s,
                             StageEvents& events) {
  if (!enabled_) return;
  for (cl_int axis = 0; axis < 2; ++axis) {  // rows first: the columns' pass combines both
    const ThicknessParams p{frame, axis, s.thicknessScale, s.thicknessMinRelative, s.thicknessMaxRelative};
    kernel_.setArg(0, p);
    q.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(roundUp(axis ? frame_.width : frame_.height, 16)),
                           cl::NDRange(16), nullptr, newEvent(events, "thickness"));
  }
}

}  // namespace ssrcl::detail
