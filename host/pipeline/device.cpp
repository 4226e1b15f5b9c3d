#include "ssrcl/device.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "device_impl.hpp"
#include "embedded_kernels.hpp"
#include "program_cache.hpp"

namespace ssrcl {
namespace detail {

const char* clErrorName(cl_int code) {
  switch (code) {
#define SSRCL_CL_CASE(name) \
  case name:                \
    return #name;
    SSRCL_CL_CASE(CL_DEVICE_NOT_FOUND)
    SSRCL_CL_CASE(CL_DEVICE_NOT_AVAILABLE)
    SSRCL_CL_CASE(CL_COMPILER_NOT_AVAILABLE)
    SSRCL_CL_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    SSRCL_CL_CASE(CL_OUT_OF_RESOURCES)
    SSRCL_CL_CASE(CL_OUT_OF_HOST_MEMORY)
    SSRCL_CL_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
    SSRCL_CL_CASE(CL_BUILD_PROGRAM_FAILURE)
    SSRCL_CL_CASE(CL_INVALID_VALUE)
    SSRCL_CL_CASE(CL_INVALID_DEVICE)
    SSRCL_CL_CASE(CL_INVALID_CONTEXT)
    SSRCL_CL_CASE(CL_INVALID_COMMAND_QUEUE)
    SSRCL_CL_CASE(CL_INVALID_MEM_OBJECT)
    SSRCL_CL_CASE(CL_INVALID_BUFFER_SIZE)
    SSRCL_CL_CASE(CL_INVALID_PROGRAM)
    SSRCL_CL_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
    SSRCL_CL_CASE(CL_INVALID_KERNEL_NAME)
    SSRCL_CL_CASE(CL_INVALID_KERNEL)
    SSRCL_CL_CASE(CL_INVALID_ARG_INDEX)
    SSRCL_CL_CASE(CL_INVALID_ARG_VALUE)
    SSRCL_CL_CASE(CL_INVALID_ARG_SIZE)
    SSRCL_CL_CASE(CL_INVALID_KERNEL_ARGS)
    SSRCL_CL_CASE(CL_INVALID_WORK_DIMENSION)
    SSRCL_CL_CASE(CL_INVALID_WORK_GROUP_SIZE)
    SSRCL_CL_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    SSRCL_CL_CASE(CL_INVALID_EVENT)
    SSRCL_CL_CASE(CL_PLATFORM_NOT_FOUND_KHR)
#undef SSRCL_CL_CASE
    default:
      return "unknown OpenCL error";
  }
}

void rethrowClError(const cl::Error& e, const std::string& context) {
  cl_int code = e.err();
  std::string message =
      context + ": " + e.what() + " failed with " + clErrorName(code) + " (" + std::to_string(code) + ")";
  bool oom = code == CL_MEM_OBJECT_ALLOCATION_FAILURE || code == CL_OUT_OF_RESOURCES || code == CL_OUT_OF_HOST_MEMORY ||
             code == CL_INVALID_BUFFER_SIZE;
  throw Error(oom ? ErrorCode::OutOfMemory : ErrorCode::OpenCL, message);
}

namespace {

std::string mebibytes(unsigned long long bytes) {
  return std::to_string((bytes + (1ull << 20) - 1) >> 20) + " MiB";
}

}  // namespace

void checkDeviceMemory(const Device::Impl& device, unsigned long long largestBuffer, unsigned long long totalBytes,
                       const std::string& what) {
  unsigned long long maxAlloc = 0, global = 0;
  try {
    maxAlloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    global = device.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  } catch (const cl::Error& e) {
    rethrowClError(e, "querying the memory of '" + device.info.name + "'");
  }
  if (largestBuffer > maxAlloc)
    throw Error(ErrorCode::OutOfMemory, what + " needs a device buffer of " + mebibytes(largestBuffer) + " but '" +
                                            device.info.name + "' allows at most " + mebibytes(maxAlloc) +
                                            " per buffer");
  // A CPU device's memory is the host's: PoCL reports a fraction of it as its global memory but
  // does not hold allocations to that, so the bound there is the machine's physical memory.
  unsigned long long limit = global;
  if (!device.info.isGpu) {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && pageSize > 0) limit = std::max(limit, static_cast<unsigned long long>(pages) * pageSize);
  }
  if (totalBytes > limit)
    throw Error(ErrorCode::OutOfMemory, what + " needs " + mebibytes(totalBytes) + " of device memory but '" +
                                            device.info.name + "' has " + mebibytes(limit));
}

}  // namespace detail

namespace {

struct Found {
  DeviceInfo info;
  cl::Device device;
};

DeviceInfo describe(const cl::Device& d, int index) {
  DeviceInfo info;
  info.index = index;
  info.platform = cl::Platform(d.getInfo<CL_DEVICE_PLATFORM>()).getInfo<CL_PLATFORM_NAME>();
  info.name = d.getInfo<CL_DEVICE_NAME>();
  info.version = d.getInfo<CL_DEVICE_VERSION>();
  info.isGpu = (d.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0;
  info.globalMemory = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  info.computeUnits = static_cast<int>(d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
  return info;
}

std::vector<Found> enumerate() {
  std::vector<Found> found;
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    // The ICD loader reports "no platform" as an error; for us it is simply an empty list.
    if (e.err() == CL_PLATFORM_NOT_FOUND_KHR) return found;
    throw;
  }
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices is not an error either
    }
    for (const cl::Device& d : devices) found.push_back({describe(d, static_cast<int>(found.size())), d});
  }
  return found;
}

// PoCL (the usual CPU driver) lists no device when it cannot create its kernel cache
// (POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else $HOME/.cache/pocl): a farm node with a
// read-only HOME looks like one without a driver. Returns that directory when it cannot be
// created or written, else "". Only asked once no device was found.
std::string unwritablePoclCache() {
  namespace fs = std::filesystem;
  fs::path dir;
  if (const char* d = std::getenv("POCL_CACHE_DIR"); d && *d)
    dir = d;
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    dir = fs::path(x) / "pocl";
  else if (const char* h = std::getenv("HOME"); h && *h)
    dir = fs::path(h) / ".cache" / "pocl";
  else
    return "";
  std::error_code ec;
  fs::create_directories(dir, ec);  // as PoCL would
  return !ec && access(dir.c_str(), W_OK) == 0 ? "" : dir.string();
}

std::string noDeviceMessage() {
  const std::string cache = unwritablePoclCache();
  if (!cache.empty())
    return "no OpenCL device found: PoCL cannot create its kernel cache in '" + cache +
           "' (not writable); set POCL_CACHE_DIR to a writable directory (e.g. POCL_CACHE_DIR=$TMPDIR/pocl)";
  return "no OpenCL device found (is an OpenCL driver such as pocl-opencl-icd installed?)";
}

std::vector<Found> enumerateOrThrow() {
  try {
    return enumerate();
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "listing OpenCL devices");
  }
}

std::shared_ptr<Device::Impl> open(Found found) {
  auto impl = std::make_shared<Device::Impl>();
  try {
    impl->info = std::move(found.info);
    impl->device = found.device;
    impl->context = cl::Context(impl->device);
    impl->queue = cl::CommandQueue(impl->context, impl->device, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "opening OpenCL device '" + impl->info.name + "'");
  }
  return impl;
}

}  // namespace

const cl::Program& Device::Impl::program(const std::vector<std::string>& sources,
                                         const std::vector<std::string>& defines) {
  // SSRCL_KERNEL_BUILD_OPTIONS adds OpenCL compiler options, for diagnosing a driver (e.g.
  // -cl-opt-disable); they come last, so they can override the variant's defines.
  // -cl-kernel-arg-info: the stages check their bindings against the kernels (checkKernelArgs).
  std::string options = "-cl-std=CL1.2 -cl-kernel-arg-info";
  for (const std::string& d : defines) options += " -D" + d;
  if (const char* extra = std::getenv("SSRCL_KERNEL_BUILD_OPTIONS")) options += std::string(" ") + extra;
  std::string key = options;
  for (const std::string& s : sources) key += " " + s;

  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;
  std::string source;
  for (const std::string& name : sources) source += std::string("#line 1 \"") + name + "\"\n" + detail::embeddedKernel(name) + "\n";
  if (cl::Program cached = detail::cachedProgram(context, device, source, options); cached())
    return programs_.emplace(key, std::move(cached)).first->second;
  cl::Program program;
  try {
    program = cl::Program(context, source);
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "creating the ssrcl OpenCL program");
  }
  try {
    program.build({device}, options.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    } catch (const cl::Error&) {
      log = "(the driver gave no build log)";
    }
    if (log.find_first_not_of(" \t\r\n") == std::string::npos) log = "(the driver gave an empty build log)";
    throw Error(ErrorCode::KernelBuild,
                "OpenCL kernels failed to build on '" + info.name + "': " + detail::clErrorName(e.err()) +
                    " (options: " + options + ")",
                log);
  }
  detail::storeProgram(program, device, source, options);
  return programs_.emplace(key, std::move(program)).first->second;
}

std::vector<DeviceInfo> Device::list() {
  std::vector<DeviceInfo> infos;
  for (auto& f : enumerateOrThrow()) infos.push_back(f.info);
  return infos;
}

Device::Device(DeviceType type) {
  auto found = enumerateOrThrow();
  if (found.empty())
    throw Error(ErrorCode::NoDevice, noDeviceMessage());
  auto pick = [&](bool gpu) -> const Found* {
    for (const auto& f : found)
      if (f.info.isGpu == gpu) return &f;
    return nullptr;
  };
  const Found* chosen = nullptr;
  switch (type) {
    case DeviceType::GPU:
      chosen = pick(true);
      break;
    case DeviceType::CPU:
      chosen = pick(false);
      break;
    case DeviceType::Default:
      chosen = pick(true) ? pick(true) : &found.front();
      break;
  }
  if (!chosen)
    throw Error(ErrorCode::NoDevice,
                std::string("no OpenCL ") + (type == DeviceType::GPU ? "GPU" : "CPU") + " device found");
  impl_ = open(*chosen);
}

Device::Device(int index) {
  auto found = enumerateOrThrow();
  if (index < 0 || index >= static_cast<int>(found.size()))
    throw Error(ErrorCode::NoDevice, "no OpenCL device with index " + std::to_string(index) + " (" +
                                         std::to_string(found.size()) + " found; see `ssrcl devices`)");
  impl_ = open(found[index]);
}

Device::Device(_cl_device_id* device, _cl_context* context, _cl_command_queue* queue) {
  auto impl = std::make_shared<Impl>();
  try {
    impl->device = cl::Device(device, true);  // retained: the caller may release theirs
    impl->context = cl::Context(context, true);
    impl->queue = cl::CommandQueue(queue, true);
    impl->info = describe(impl->device, -1);
    const auto properties = impl->queue.getInfo<CL_QUEUE_PROPERTIES>();
    if (!(properties & CL_QUEUE_PROFILING_ENABLE) || (properties & CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE))
      throw Error(ErrorCode::InvalidArgument,
                  "the caller's OpenCL queue must be in order and have CL_QUEUE_PROFILING_ENABLE (stage times)");
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "using the caller's OpenCL device, context and queue");
  }
  impl_ = std::move(impl);
}

const DeviceInfo& Device::info() const { return impl_->info; }

}  // namespace ssrcl
