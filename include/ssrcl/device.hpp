#pragma once
#include <memory>
#include <string>
#include <vector>

// OpenCL's handle types (cl_device_id is _cl_device_id*, ...), without the OpenCL headers.
struct _cl_device_id;
struct _cl_context;
struct _cl_command_queue;

namespace ssrcl {
namespace detail {
struct DeviceAccess;
}

enum class DeviceType { Default, CPU, GPU };

struct DeviceInfo {
  int index = 0;  // global index across all platforms, as `ssrcl devices` lists it
  std::string platform;
  std::string name;
  std::string version;
  bool isGpu = false;
  unsigned long long globalMemory = 0;
  int computeUnits = 0;
};

// An OpenCL device with its context, profiling queue and compiled-program cache.
// Like an OIDN device: create once, share among pipelines, cheap to copy (shared handle).
class Device {
 public:
  // Every device of every platform, in a stable order. Empty (not an error) when none.
  static std::vector<DeviceInfo> list();

  // The preferred device of a type: GPU first for Default, else the first CPU.
  explicit Device(DeviceType type = DeviceType::Default);
  // The device with a global index from list(); throws Error(NoDevice) when out of range.
  explicit Device(int index);
  // The caller's OpenCL device, context and queue (retained while this Device lives), to share
  // them with the caller's own work: pipelines enqueue on `queue`, which must be in order and
  // created with CL_QUEUE_PROFILING_ENABLE (Error(InvalidArgument) otherwise). info().index is -1.
  Device(_cl_device_id* device, _cl_context* context, _cl_command_queue* queue);

  const DeviceInfo& info() const;

  struct Impl;

 private:
  friend struct detail::DeviceAccess;  // the library's stages reach the OpenCL objects
  std::shared_ptr<Impl> impl_;
};

// A device by name, as `ssrcl --device` takes it: an index from Device::list(), "cpu", "gpu", or
// "default" (or empty). Throws Error(InvalidArgument) for another name.
Device openDevice(const std::string& name);

}  // namespace ssrcl
