#pragma once
// Setup (kernels/setup.cl): uploads the passes and turns them into what tracing needs: view-space
// points and normals, the surface planes the trace tests, level 0 of the HZB and colour pyramids,
// ray counts and the lists of pixels and tiles to work on.
#include "frame_resources.hpp"
#include "host_backed_buffer.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::detail {

class SetupStage {
 public:
  struct Inputs {  // packed floats
    const float* color;
    const float* depth;
    const float* normal;
    const float* roughness;  // null with a constant roughness
  };
  // The counters setup fills (SSRCL_COUNT_*).
  struct Counts {
    cl_int listedPixels = 0, rays = 0, listedTiles = 0, tracedPixels = 0;
  };

  static const StageAccess access;

  void configure(Device::Impl& device);
  // fillNormals: the environment fill's normals (Role::FillNormals) are written; no buffer without.
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame, int colorChannels,
            bool roughnessImage, bool fillNormals);
  void bind(const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const Inputs& in, const SetupParams& params, StageEvents& events);
  Counts readCounts(cl::CommandQueue& q);  // waits for the setup to finish
  static SetupParams params(const FrameConstants& frame, const TraceSettings& s, int colorChannels);

 private:
  FrameShape frame_;
  int colorChannels_ = 0;
  bool fillNormals_ = false;
  Device::Impl* device_ = nullptr;
  cl::Kernel kernel_;
  HostInput colorIn_, depthIn_, normalIn_, roughnessIn_;
  cl::Buffer counts_;
};

}  // namespace ssrcl::detail
