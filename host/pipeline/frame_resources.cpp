#include "frame_resources.hpp"

#include <algorithm>

#include "ssrcl/error.hpp"

namespace ssrcl::detail {
namespace {

bool declares(const std::vector<Role>& roles, Role role) {
  return std::find(roles.begin(), roles.end(), role) != roles.end();
}

}  // namespace

const char* roleName(Role role) {
  static const char* const names[] = {"positions",         "normals",        "fill normals", "planes",
                                      "back guess",        "pixel rays",     "ray list",     "tile list",
                                      "depth pyramid",     "pyramid levels", "back pyramid", "colour pyramid",
                                      "ray hits",          "ray radiance",   "ray states",   "resolved rgba",
                                      "resolved distance", "reflection",     "distance",     "view share"};
  static_assert(sizeof(names) / sizeof(names[0]) == size_t(Role::Count), "a name per role");
  return names[size_t(role)];
}

void FrameResources::beginPlan() { planner_.fill(nullptr); }

void FrameResources::plan(const StageAccess& access, DeviceBuffers& buffers, Role role, size_t bytes,
                          cl_mem_flags flags) {
  if (!declares(access.reads, role) && !declares(access.writes, role))
    throw Error(ErrorCode::InvalidOperation, std::string(access.stage) + " plans the frame's " + roleName(role) +
                                                 " but does not declare it");
  const char*& planner = planner_[size_t(role)];
  if (planner)
    throw Error(ErrorCode::InvalidOperation, std::string("the frame's ") + roleName(role) + " is planned by both " +
                                                 planner + " and " + access.stage);
  planner = access.stage;
  buffers.add(buffers_[size_t(role)], bytes, flags);
}

const cl::Buffer& FrameResources::planned(const StageAccess& access, Role role) const {
  if (!planner_[size_t(role)])
    throw Error(ErrorCode::InvalidOperation, std::string(access.stage) + " binds the frame's " + roleName(role) +
                                                 ", which no stage planned");
  return buffers_[size_t(role)];
}

const cl::Buffer& FrameResources::read(const StageAccess& access, Role role) const {
  if (!declares(access.reads, role) && !declares(access.writes, role))
    throw Error(ErrorCode::InvalidOperation, std::string(access.stage) + " binds the frame's " + roleName(role) +
                                                 " but does not declare it");
  return planned(access, role);
}

const cl::Buffer& FrameResources::write(const StageAccess& access, Role role) const {
  if (!declares(access.writes, role))
    throw Error(ErrorCode::InvalidOperation, std::string(access.stage) + " writes the frame's " + roleName(role) +
                                                 " but does not declare writing it");
  return planned(access, role);
}

}  // namespace ssrcl::detail
