#pragma once
// Environment fill (kernels/environment.cl), after the resolve and filter: the part of each
// pixel's lobe the screen did not hold takes the prefiltered environment's radiance. Runs only
// with an environment set (Pipeline::setEnvironment).
#include "frame_resources.hpp"
#include "ssrcl/environment.hpp"

namespace ssrcl::detail {

class EnvironmentStage {
 public:
  // Throws Error(InvalidArgument) for a map whose levels are not 2:1 RGB images (at least two).
  static void validate(const EnvironmentMap& map);
  static const StageAccess access;
  void configure(Device::Impl& device, const TraceSettings& s, const EnvironmentMap* map);  // null: off
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  // Uploads the map and binds the frame's points and normals and the reflection it fills.
  void bind(cl::CommandQueue& q, const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, const glm::dmat4& view, const TraceSettings& s,
               StageEvents& events);

 private:
  const EnvironmentMap* map_ = nullptr;
  FrameShape frame_;
  cl::Kernel kernel_;
  std::vector<HzbLevel> packed_;  // the map's levels in one buffer, as the HZB's
  cl::Buffer texels_, levels_;
};

}  // namespace ssrcl::detail
