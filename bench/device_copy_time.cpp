#include "device_copy_time.hpp"

#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>
#include <stdexcept>
#include <vector>

namespace ssrcl::bench {

struct DeviceCopyTime::Impl {
  cl::Context context;
  cl::CommandQueue queue;
  cl::Buffer from, to;
  size_t bytes;
};

namespace {

// The device Device::list() describes as `info`: its own context, so the copy runs on the same
// hardware as the pipeline without reaching into the library's objects.
cl::Device findDevice(const DeviceInfo& info) {
  std::vector<cl::Platform> platforms;
  cl::Platform::get(&platforms);
  for (const cl::Platform& platform : platforms) {
    if (platform.getInfo<CL_PLATFORM_NAME>() != info.platform) continue;
    std::vector<cl::Device> devices;
    platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    for (const cl::Device& d : devices)
      if (d.getInfo<CL_DEVICE_NAME>() == info.name) return d;
  }
  throw std::runtime_error("device copy timing: no OpenCL device named '" + info.name + "' on platform '" +
                           info.platform + "'");
}

}  // namespace

DeviceCopyTime::DeviceCopyTime(const DeviceInfo& info, size_t bytes) : impl_(new Impl) {
  const cl::Device device = findDevice(info);
  impl_->context = cl::Context(device);
  impl_->queue = cl::CommandQueue(impl_->context, device, CL_QUEUE_PROFILING_ENABLE);
  impl_->from = cl::Buffer(impl_->context, CL_MEM_READ_WRITE, bytes);
  impl_->to = cl::Buffer(impl_->context, CL_MEM_READ_WRITE, bytes);
  impl_->bytes = bytes;
  // First touch: lazily allocating drivers (PoCL) would otherwise time the allocation.
  impl_->queue.enqueueFillBuffer(impl_->from, cl_float(1.0f), 0, bytes);
  impl_->queue.enqueueFillBuffer(impl_->to, cl_float(0.0f), 0, bytes);
  impl_->queue.finish();
}

DeviceCopyTime::~DeviceCopyTime() = default;

double DeviceCopyTime::run() {
  cl::Event done;
  impl_->queue.enqueueCopyBuffer(impl_->from, impl_->to, 0, 0, impl_->bytes, nullptr, &done);
  done.wait();
  return double(done.getProfilingInfo<CL_PROFILING_COMMAND_END>() - done.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
         1e-6;
}

}  // namespace ssrcl::bench
