#pragma once
// Device buffers whose memory the library allocates itself where the device's memory is the
// host's (CPU devices): large ones on transparent huge pages.
#include <cstddef>

#include "device_impl.hpp"

namespace ssrcl::detail {

// A buffer of `bytes` with `flags`. On a device sharing the host's memory, buffers of a huge
// page and up are allocated on 2 MiB boundaries, marked for transparent huge pages and handed to
// the driver as its memory (CL_MEM_USE_HOST_PTR); freed when the driver releases the buffer.
// Elsewhere, and for smaller buffers, the driver allocates as usual.
cl::Buffer newDeviceBuffer(Device::Impl& device, cl_mem_flags flags, size_t bytes);

}  // namespace ssrcl::detail
