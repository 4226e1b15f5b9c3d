#pragma once
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "opencl.hpp"
#include "ssrcl/device.hpp"

namespace ssrcl {

struct Device::Impl {
  DeviceInfo info;
  cl::Device device;
  cl::Context context;
  cl::CommandQueue queue;  // in-order, with profiling for per-stage times

  // A program of kernels/ sources (in the order given) built with `defines` (e.g. "SSRCL_TRACER=1"),
  // compiled on first use and shared by pipelines: one per (sources, defines).
  const cl::Program& program(const std::vector<std::string>& sources, const std::vector<std::string>& defines = {});

 private:
  std::mutex mutex_;
  std::map<std::string, cl::Program> programs_;
};

namespace detail {

struct DeviceAccess {
  static Device::Impl& impl(const Device& device) { return *device.impl_; }
};

// Throws Error(OutOfMemory), naming `what` (e.g. "a 8192x8192 frame") and the sizes, when a
// buffer of `largestBuffer` bytes exceeds the device's CL_DEVICE_MAX_MEM_ALLOC_SIZE or all
// buffers together (`totalBytes`) its CL_DEVICE_GLOBAL_MEM_SIZE (for CPU devices, whose memory
// is the host's, the larger of that and the machine's physical memory). Drivers that allocate
// lazily (PoCL, most GPU drivers) would otherwise fail later, or not at all until the host runs out.
void checkDeviceMemory(const Device::Impl& device, unsigned long long largestBuffer, unsigned long long totalBytes,
                       const std::string& what);

}  // namespace detail
}  // namespace ssrcl
