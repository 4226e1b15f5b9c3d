#include "host_backed_buffer.hpp"

#include <cstdlib>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace ssrcl::detail {
namespace {

constexpr size_t hugePage = size_t(2) << 20;

void CL_CALLBACK freeHostMemory(cl_mem, void* memory) { std::free(memory); }

}  // namespace

cl::Buffer newDeviceBuffer(Device::Impl& device, cl_mem_flags flags, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Each first touch of a 4 KiB page is a fault: a 1080p frame's buffers took some 190,000, 13%
  // of the process's CPU on a virtual machine (perf: exc_page_fault under the kernels, the
  // driver's fills and copies). One fault a 2 MiB page instead: docs/BENCHMARKS.md "Huge pages".
  if (!device.info.isGpu && bytes >= hugePage && device.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>()) {
    const size_t rounded = (bytes + hugePage - 1) / hugePage * hugePage;
    if (void* memory = std::aligned_alloc(hugePage, rounded)) {
      madvise(memory, rounded, MADV_HUGEPAGE);  // advice: where refused, plain pages serve
      cl_int status = CL_SUCCESS;
      cl_mem mem = clCreateBuffer(device.context(), flags | CL_MEM_USE_HOST_PTR, bytes, memory, &status);
      if (status == CL_SUCCESS && clSetMemObjectDestructorCallback(mem, freeHostMemory, memory) == CL_SUCCESS)
        return cl::Buffer(mem);  // takes the reference clCreateBuffer gave
      if (mem) clReleaseMemObject(mem);
      std::free(memory);
    }
  }
#endif
  return cl::Buffer(device.context, flags, bytes);
}

}  // namespace ssrcl::detail
