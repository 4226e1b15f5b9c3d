#pragma once
// Setup (kernels/setup.cl): uploads the passes and turns them into what tracing needs: view-space
// points and normals, the surface planes the trace tests, level 0 of the HZB and colour pyramids,
// ray counts and the lists of pixels and tiles to work on.
#include "ssrcl/pipeline.hpp"
#include "stage_support.hpp"

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

  void configure(Device::Impl& device);
  void plan(DeviceBuffers& buffers, const FrameShape& frame, int colorChannels, bool roughnessImage);
  void bind(const cl::Buffer& hzb, const cl::Buffer& colorPyramid);
  void enqueue(cl::CommandQueue& q, const Inputs& in, const SetupParams& params, StageEvents& events);
  Counts readCounts(cl::CommandQueue& q);  // waits for the setup to finish
  static SetupParams params(const FrameShape& frame, const CameraConstants& camera,
                                    const TraceSettings& s, int colorChannels);

  // Its products, read by the later stages.
  cl::Buffer positions;  // view-space point, planar depth in w (SSRCL_NO_SURFACE: none)
  cl::Buffer normals;    // view-space normal, roughness in w
  cl::Buffer pixelRays, rayList, tileList, counts;
  cl::Buffer planes;  // surface plane over thickness, the trace's hit test (kernels/surface_plane.cl)

 private:
  FrameShape frame_;
  int colorChannels_ = 0;
  cl::Kernel kernel_;
  cl::Buffer colorIn_, depthIn_, normalIn_, roughnessIn_;
};

}  // namespace ssrcl::detail
