#pragma once
#include <map>
#include <mutex>

#include "opencl.hpp"
#include "ssrcl/device.hpp"

namespace ssrcl {

struct Device::Impl {
  DeviceInfo info;
  cl::Device device;
  cl::Context context;
  cl::CommandQueue queue;  // in-order, with profiling for per-stage times

  // The ssrcl program built for this device, compiled on first use and shared by pipelines.
  const cl::Program& program();

 private:
  std::mutex mutex_;
  cl::Program program_;
  bool built_ = false;
};

}  // namespace ssrcl
