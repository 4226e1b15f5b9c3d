#pragma once
#include "opencl.hpp"
#include "ssrcl/environment.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::detail {

// The environment-fill stage (kernels/environment.cl), run after the resolve: misses take the
// prefiltered environment's radiance. The pipeline uploads the map at commit and enqueues the
// stage on its reflection at execute.
class EnvironmentFill {
 public:
  // Throws Error(InvalidArgument) for a map whose levels are not 2:1 RGB images (at least two).
  static void validate(const EnvironmentMap& map);
  // Device bytes the map needs (for the pipeline's memory check).
  static size_t deviceBytes(const EnvironmentMap& map);
  void upload(const cl::Context& context, const cl::Program& program, const EnvironmentMap& map);
  // view: the camera's world -> view matrix. Fills `rgba` (float4 per pixel) in place.
  cl::Event enqueue(cl::CommandQueue& queue, cl_int2 size, const glm::dmat4& view, const TraceSettings& settings,
                    const cl::Buffer& positions, const cl::Buffer& normals, cl::Buffer& rgba);

 private:
  cl::Kernel kernel_;
  cl::Buffer texels_, levels_;
  int levelCount_ = 0;
};

}  // namespace ssrcl::detail
