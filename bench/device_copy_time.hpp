#pragma once
#include <cstddef>
#include <memory>

#include "ssrcl/device.hpp"

namespace ssrcl::bench {

// Device time of clEnqueueCopyBuffer between two device buffers of `bytes` each, on the OpenCL
// device `info` names (platform and device name): the memory floor of one pass over a buffer of
// that size, against which bench/ssrcl_roofline sets the HZB (which reads the depth buffer once
// and writes a third of it).
class DeviceCopyTime {
 public:
  // Throws std::runtime_error naming the device when no OpenCL device matches `info`.
  DeviceCopyTime(const DeviceInfo& info, size_t bytes);
  ~DeviceCopyTime();
  DeviceCopyTime(const DeviceCopyTime&) = delete;
  DeviceCopyTime& operator=(const DeviceCopyTime&) = delete;

  // One copy, waited for; its profiled device time in milliseconds.
  double run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssrcl::bench
