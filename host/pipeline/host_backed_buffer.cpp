#include "host_backed_buffer.hpp"

#include <cstdint>

namespace ssrcl::detail {
namespace {

// What host memory a buffer can be on this device: aligned as its buffers (0: none can).
size_t hostAlignment(Device::Impl& device) {
  return sharesHostMemory(device) ? device.device.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / 8 : 0;
}

bool aligned(const void* memory, size_t alignment) {
  return alignment && reinterpret_cast<std::uintptr_t>(memory) % alignment == 0;
}

}  // namespace

bool sharesHostMemory(Device::Impl& device) {
  return !device.info.isGpu && device.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
}

cl::Buffer newDeviceBuffer(Device::Impl& device, cl_mem_flags flags, size_t bytes, void* host) {
  if (host && aligned(host, hostAlignment(device)))
    return cl::Buffer(device.context, flags | CL_MEM_USE_HOST_PTR, bytes, host);
  return cl::Buffer(device.context, flags, bytes);
}

void HostInput::plan(Device::Impl& device, DeviceBuffers& buffers, size_t bytes) {
  context_ = device.context;
  alignment_ = hostAlignment(device);
  buffers.add(own_, alignment_ ? 0 : bytes, CL_MEM_READ_ONLY);
}

const cl::Buffer& HostInput::put(cl::CommandQueue& q, const void* data, size_t bytes, StageEvents& events) {
  frame_ = cl::Buffer();
  if (!data) return own_;
  if (!alignment_) {
    q.enqueueWriteBuffer(own_, CL_FALSE, 0, bytes, data, nullptr, newEvent(events, "upload"));
    return own_;
  }
  // Pixels off the device's alignment (a caller's own allocation) are copied once, into memory
  // the driver allocates for this frame.
  frame_ = cl::Buffer(context_, CL_MEM_READ_ONLY | (aligned(data, alignment_) ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR), bytes,
                      const_cast<void*>(data));  // read only: the kernels never write it
  return frame_;
}

}  // namespace ssrcl::detail
