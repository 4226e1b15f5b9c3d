#include "environment_stage.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include "ssrcl/error.hpp"

namespace ssrcl::detail {

const StageAccess EnvironmentStage::access{"environment", {Role::Positions, Role::FillNormals}, {Role::Reflection}};

void EnvironmentStage::validate(const EnvironmentMap& map) {
  const std::string name = map.source.empty() ? "environment" : map.source;
  if (map.levels.size() < 2)
    throw Error(ErrorCode::InvalidArgument, name + ": a prefiltered environment has at least two levels");
  for (const Image& level : map.levels)
    if (level.channels != 3 || level.width < 1 || level.width != 2 * level.height ||
        level.data.size() != size_t(level.width) * level.height * 3)
      throw Error(ErrorCode::InvalidArgument,
                  name + ": every environment level must be a 2:1 RGB image (use prefilterEnvironment)");
}

void EnvironmentStage::configure(Device::Impl& device, const TraceSettings& s, const EnvironmentMap* map) {
  map_ = map;
  if (!map_) return;
  kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "environment.cl"},
                                      {roughnessMappingDefine(s.roughnessMapping)}),
                       "environment_fill");
  packed_.clear();
  int offset = 0;
  for (const Image& level : map_->levels) {
    packed_.push_back({offset, level.width, level.height, 0});
    offset += level.width * level.height;
  }
}

void EnvironmentStage::plan(DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  const size_t texels = map_ ? size_t(packed_.back().offset) + size_t(packed_.back().width) * packed_.back().height : 0;
  buffers.add(texels_, texels * 3 * sizeof(float), CL_MEM_READ_ONLY);
  buffers.add(levels_, packed_.size() * sizeof(HzbLevel), CL_MEM_READ_ONLY);
}

void EnvironmentStage::bind(cl::CommandQueue& q, const FrameResources& resources) {
  if (!map_) return;
  size_t offset = 0;
  for (const Image& level : map_->levels) {
    q.enqueueWriteBuffer(texels_, CL_TRUE, offset, level.data.size() * sizeof(float), level.data.data());
    offset += level.data.size() * sizeof(float);
  }
  q.enqueueWriteBuffer(levels_, CL_TRUE, 0, packed_.size() * sizeof(HzbLevel), packed_.data());
  bindArgs(kernel_, 1, "positions, normals, texels, levels, rgba", resources.read(access, Role::Positions),
           resources.read(access, Role::FillNormals), texels_, levels_, resources.write(access, Role::Reflection));
}

void EnvironmentStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, const glm::dmat4& view,
                               const TraceSettings& s, StageEvents& events) {
  if (!map_) return;
  // View -> world is the inverse of the view's rotation (the kernel's lookup ignores a uniform
  // scale); then the mapping's rotation about +Z (a Mapping node's Rotation Z).
  const glm::dmat3 toWorld = glm::inverse(glm::dmat3(view));
  const glm::dmat3 rotation(
      glm::rotate(glm::dmat4(1.0), glm::radians(double(s.environmentRotation)), glm::dvec3(0, 0, 1)));
  EnvironmentParams p{};
  p.frame = frame;
  toRowMajor(glm::dmat4(rotation * toWorld), p.view_to_world);
  p.level_count = static_cast<shared::ssrcl_int>(packed_.size());
  p.intensity = s.environmentIntensity;
  kernel_.setArg(0, p);
  q.enqueueNDRangeKernel(kernel_, cl::NullRange, frame_.tiled2d(), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "environment"));
}

}  // namespace ssrcl::detail
