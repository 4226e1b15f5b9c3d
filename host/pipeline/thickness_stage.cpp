#include "thickness_stage.hpp"

namespace ssrcl::detail {

namespace {

// known_thickness's arguments after its parameters; the back-face depth is set again each frame.
const KernelArgList kKnownArgs{1, "positions, back, planes, guess"};

}  // namespace

const StageAccess ThicknessStage::access{"thickness", {Role::Positions}, {Role::Planes, Role::BackGuess}};

void ThicknessStage::configure(Device::Impl& device, const TraceSettings& s, bool backDepth) {
  device_ = &device;
  adaptive_ = s.thicknessModel == ThicknessModel::Adaptive;
  backDepth_ = backDepth;
  if (!adaptive_ && !backDepth_) return;
  const cl::Program program = device.program({"ssrcl_shared.h", "common.cl", "surface_plane.cl", "thickness.cl"});
  if (adaptive_) kernel_ = cl::Kernel(program, "surface_thickness");
  if (backDepth_) known_ = cl::Kernel(program, "known_thickness");
}

void ThicknessStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  buffers.add(rowRuns_, adaptive_ ? frame.pixels() * sizeof(cl_float2) : 0);
  back_.plan(*device_, buffers, backDepth_ ? frame.pixels() * sizeof(float) : 0);
  resources.plan(access, buffers, Role::BackGuess, backDepth_ ? frame.pixels() * sizeof(float) : 0);
}

void ThicknessStage::bind(const FrameResources& resources) {
  if (adaptive_)
    bindArgs(kernel_, 1, "positions, row, planes", resources.read(access, Role::Positions), rowRuns_,
             resources.write(access, Role::Planes));
  if (backDepth_)
    bindArgs(known_, kKnownArgs, resources.read(access, Role::Positions), back_.own(),
             resources.write(access, Role::Planes), resources.write(access, Role::BackGuess));
}

void ThicknessStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, const TraceSettings& s,
                             const float* backDepth, bool orthographic, StageEvents& events) {
  ThicknessParams p{frame, 0, s.thicknessScale, s.thicknessMinRelative, s.thicknessMaxRelative, orthographic};
  for (cl_int axis = 0; adaptive_ && axis < 2; ++axis) {  // rows first: the columns' pass combines both
    p.axis = axis;
    kernel_.setArg(0, p);
    q.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(roundUp(axis ? frame_.width : frame_.height, 16)),
                           cl::NDRange(16), nullptr, newEvent(events, "thickness"));
  }
  if (!backDepth_) return;
  known_.setArg(kKnownArgs["back"], back_.put(q, backDepth, frame_.pixels() * sizeof(float), events));
  known_.setArg(0, p);
  q.enqueueNDRangeKernel(known_, cl::NullRange, cl::NDRange(roundUp(frame_.pixels(), 64)), cl::NDRange(64),
                         nullptr, newEvent(events, "thickness"));
}

}  // namespace ssrcl::detail
