#include "environment_fill.hpp"

#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "kernel_args.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {
namespace {

// Mirrors HzbLevel in kernels/common.cl, which the fill reuses for its packed levels.
struct PackedLevel {
  cl_int offset, width, height, pad;
};

size_t texelCount(const EnvironmentMap& map) {
  size_t n = 0;
  for (const Image& level : map.levels) n += size_t(level.width) * level.height;
  return n;
}

}  // namespace

void EnvironmentFill::validate(const EnvironmentMap& map) {
  const std::string name = map.source.empty() ? "environment" : map.source;
  if (map.levels.size() < 2)
    throw Error(ErrorCode::InvalidArgument, name + ": a prefiltered environment has at least two levels");
  for (const Image& level : map.levels)
    if (level.channels != 3 || level.width < 1 || level.width != 2 * level.height ||
        level.data.size() != size_t(level.width) * level.height * 3)
      throw Error(ErrorCode::InvalidArgument,
                  name + ": every environment level must be a 2:1 RGB image (use prefilterEnvironment)");
}

size_t EnvironmentFill::deviceBytes(const EnvironmentMap& map) {
  return texelCount(map) * 3 * sizeof(float) + map.levels.size() * sizeof(PackedLevel);
}

void EnvironmentFill::upload(const cl::Context& context, const cl::Program& program, const EnvironmentMap& map) {
  std::vector<PackedLevel> packed;
  std::vector<float> texels;
  texels.reserve(texelCount(map) * 3);
  for (const Image& level : map.levels) {
    packed.push_back({cl_int(texels.size() / 3), level.width, level.height, 0});
    texels.insert(texels.end(), level.data.begin(), level.data.end());
  }
  kernel_ = cl::Kernel(program, "environment_fill");
  texels_ = cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, texels.size() * sizeof(float), texels.data());
  levels_ = cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, packed.size() * sizeof(PackedLevel),
                       packed.data());
  levelCount_ = int(packed.size());
}

cl::Event EnvironmentFill::enqueue(cl::CommandQueue& queue, cl_int2 size, const glm::dmat4& view,
                                   const TraceSettings& settings, const cl::Buffer& positions,
                                   const cl::Buffer& normals, cl::Buffer& rgba) {
  // View -> world is the inverse of the view's rotation (the kernel's lookup ignores a uniform
  // scale); then the mapping's rotation about +Z (a Mapping node's Rotation Z).
  const glm::dmat3 toWorld = glm::inverse(glm::dmat3(view));
  const glm::dmat3 rotation(glm::rotate(glm::dmat4(1.0), glm::radians(double(settings.environmentRotation)),
                                        glm::dvec3(0, 0, 1)));
  const cl_float16 viewToWorld = toFloat16RowMajor(glm::dmat4(rotation * toWorld));
  const cl_int linear = settings.roughnessMapping == RoughnessMapping::Linear ? 1 : 0;
  setArgs(kernel_, size, viewToWorld, positions, normals, texels_, levels_, cl_int(levelCount_), linear,
          settings.environmentIntensity, rgba);
  cl::Event event;
  queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(roundUp(size.s[0], 8), roundUp(size.s[1], 8)),
                             cl::NDRange(8, 8), nullptr, &event);
  return event;
}

}  // namespace ssrcl::detail
