#pragma once
// Device buffers over the caller's own memory where the device's memory is the host's (CPU
// devices): inputs read and outputs written where they lie, without copies into fresh memory.
#include <cstddef>

#include "device_impl.hpp"
#include "stage_support.hpp"

namespace ssrcl::detail {

// A buffer of `bytes` with `flags`, the driver's own memory (the library's own, on huge pages,
// cost more system time than it saved: docs/BENCHMARKS.md "Huge pages"). With `host` (the
// caller's memory, which must outlive the buffer), the buffer is that memory where the device
// shares the host's and it is aligned as the device's buffers: what kernels write there is the
// caller's without a copy (after a map, as OpenCL asks).
cl::Buffer newDeviceBuffer(Device::Impl& device, cl_mem_flags flags, size_t bytes, void* host = nullptr);

// Whether `device` works in the host's memory (a CPU device): its buffers can be host memory.
bool sharesHostMemory(Device::Impl& device);

// One of the frame's input images as kernels read it. Where the device shares the host's memory,
// a buffer over the caller's pixels themselves: no copy and no fresh memory, whose first touch is
// what a 1080p frame's 75 MB of inputs cost on virtual machines (docs/BENCHMARKS.md "Fresh
// memory"). Elsewhere, a buffer of the device's own, written each frame.
class HostInput {
 public:
  // Plans the device's own buffer of `bytes`, where one is needed.
  void plan(Device::Impl& device, DeviceBuffers& buffers, size_t bytes);
  const cl::Buffer& own() const { return own_; }  // what kernels bind before the first put
  // The buffer holding `bytes` of `data` for the commands enqueued after it (a write, where there
  // is one, timed as "upload"); `data` must stay as it is until they finish. Null data: own().
  const cl::Buffer& put(cl::CommandQueue& q, const void* data, size_t bytes, StageEvents& events);

 private:
  cl::Context context_;
  size_t alignment_ = 0;  // of the device's buffers; 0: not the host's memory
  cl::Buffer own_, frame_;
};

}  // namespace ssrcl::detail
