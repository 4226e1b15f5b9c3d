#include "stage_support.hpp"

#include <algorithm>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>
#include <sstream>

#include "host_backed_buffer.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {

FrameShape::FrameShape(int w, int h)
    : width(w), height(h), tilesX((w + SSRCL_TILE - 1) / SSRCL_TILE), tilesY((h + SSRCL_TILE - 1) / SSRCL_TILE) {
  int offset = 0;
  for (;;) {
    levels.push_back({offset, w, h, 0});
    offset += w * h;
    if (w == 1 && h == 1) break;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
}

cl::NDRange FrameShape::tiled2d() const { return cl::NDRange(roundUp(width, SSRCL_TILE), roundUp(height, SSRCL_TILE)); }

FrameConstants frameConstants(const FrameShape& frame, const Camera& camera, const TraceSettings& s) {
  FrameConstants c{};
  toRowMajor(camera.projection, c.proj);
  toRowMajor(glm::inverse(camera.projection), c.inv_proj);
  // Normals go to view space with the inverse transpose, which stays right for scaled views.
  toRowMajor(glm::dmat4(glm::inverseTranspose(glm::dmat3(camera.view))), c.normal_matrix);
  c.width = frame.width;
  c.height = frame.height;
  c.tiles_x = frame.tilesX;
  c.near_plane = static_cast<float>(camera.nearPlane);
  c.far_plane = static_cast<float>(std::min(camera.farPlane, double(std::numeric_limits<float>::max())));
  c.mirror_roughness = s.mirrorRoughness;
  return c;
}

void DeviceBuffers::add(cl::Buffer& buffer, size_t bytes, cl_mem_flags flags) {
  planned_.push_back({&buffer, std::max<size_t>(bytes, 4), flags, nullptr});  // unused ones still bind
}

void DeviceBuffers::placeIn(const cl::Buffer& buffer, void* host) {
  for (Planned& b : planned_)
    if (b.buffer == &buffer && b.bytes > 4) b.host = host;  // a placeholder (planned empty) stays the driver's
}

size_t DeviceBuffers::check(Device::Impl& device, const std::string& what) const {
  size_t total = 0, largest = 0;
  for (const Planned& b : planned_) {
    total += b.bytes;
    largest = std::max(largest, b.bytes);
  }
  checkDeviceMemory(device, largest, total, what);
  return total;
}

bool DeviceBuffers::allocate(Device::Impl& device, const std::string& what) {
  const size_t total = check(device, what);
  bool changed = false;
  for (const Planned& b : planned_) {
    auto& held = allocated_[b.buffer];
    if (held == b && (*b.buffer)()) continue;
    *b.buffer = newDeviceBuffer(device, b.flags, b.bytes, b.host);
    held = b;
    changed = true;
  }
  planned_.clear();
  bytes_ = total;
  return changed;
}

cl::Event* newEvent(StageEvents& events, const std::string& stage) {
  auto& list = events[stage];
  list.emplace_back();
  return &list.back();
}

double eventMs(const cl::Event& e) {
  auto start = e.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  auto end = e.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return (end - start) * 1e-6;
}

std::string roughnessMappingDefine(RoughnessMapping m) {
  return m == RoughnessMapping::Linear ? "SSRCL_ROUGHNESS_MAPPING=SSRCL_ROUGHNESS_LINEAR"
                                       : "SSRCL_ROUGHNESS_MAPPING=SSRCL_ROUGHNESS_SQUARED";
}

size_t roundUp(size_t n, size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

void toRowMajor(const glm::dmat4& m, float out[16]) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r * 4 + c] = static_cast<float>(m[c][r]);  // glm is column-major
}

int resolveRayStride(const TraceSettings& s) { return s.denoise ? 4 : 1; }

int resolvedRays(const TraceSettings& s) {
  return s.samplesPerPixel * (2 * s.reuseRadius + 1) * (2 * s.reuseRadius + 1);
}

namespace {

std::vector<std::string> argNames(const char* names) {
  std::vector<std::string> out;
  std::istringstream list(names);
  for (std::string name; std::getline(list, name, ',');) out.push_back(name.substr(name.find_first_not_of(' ')));
  return out;
}

}  // namespace

cl_uint KernelArgList::operator[](const std::string& name) const {
  const std::vector<std::string> all = argNames(names);
  for (size_t k = 0; k < all.size(); ++k)
    if (all[k] == name) return first + cl_uint(k);
  throw Error(ErrorCode::InvalidOperation, "no kernel argument '" + name + "' among " + names);
}

void checkKernelArgs(const cl::Kernel& kernel, cl_uint first, const char* names, size_t count) {
  const std::vector<std::string> expected = argNames(names);
  const std::string kernelName = kernel.getInfo<CL_KERNEL_FUNCTION_NAME>().c_str();
  if (expected.size() != count)
    throw Error(ErrorCode::InvalidOperation, "kernel " + kernelName + ": the host binds " + std::to_string(count) +
                                                 " arguments but names " + std::to_string(expected.size()));
  const cl_uint declared = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
  if (first + count > declared)
    throw Error(ErrorCode::InvalidOperation, "kernel " + kernelName + " takes " + std::to_string(declared) +
                                                 " arguments, the host binds " + std::to_string(first + count));
  for (size_t k = 0; k < count; ++k) {
    std::string name;
    try {
      name = kernel.getArgInfo<CL_KERNEL_ARG_NAME>(cl_uint(first + k)).c_str();  // without the string's NUL
    } catch (const cl::Error& e) {
      if (e.err() == CL_KERNEL_ARG_INFO_NOT_AVAILABLE) return;
      throw;
    }
    if (name != expected[k])
      throw Error(ErrorCode::InvalidOperation, "kernel " + kernelName + ": argument " + std::to_string(first + k) +
                                                   " is '" + name + "' but the host binds '" + expected[k] + "' there");
  }
}

}  // namespace ssrcl::detail
