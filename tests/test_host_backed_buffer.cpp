// Device buffers on a CPU device (host/pipeline/host_backed_buffer.hpp): large ones live in memory
// the library allocated on 2 MiB boundaries (transparent huge pages), small ones where the driver
// puts them; both hold what is written to them, and a buffer's memory outlives copies of it.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

#include "pipeline/host_backed_buffer.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::detail;

ssrcl::Device::Impl& device() { return DeviceAccess::impl(ssrcl::test::sharedTestDevice()); }

bool hostShared() {
  return !device().info.isGpu && device().device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>();
}

void roundTrip(const cl::Buffer& buffer, size_t count) {
  std::vector<float> in(count), out(count, -1.0f);
  std::iota(in.begin(), in.end(), 0.5f);
  device().queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, count * sizeof(float), in.data());
  device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
  EXPECT_EQ(in, out);
}

TEST(HostBackedBuffer, LargeBuffersOnHugePageBoundaries) {
  const size_t count = (size_t(5) << 20) / sizeof(float);  // 5 MiB: not a whole number of 2 MiB pages
  cl::Buffer buffer = newDeviceBuffer(device(), CL_MEM_READ_WRITE, count * sizeof(float));
  EXPECT_EQ(buffer.getInfo<CL_MEM_SIZE>(), count * sizeof(float));
  if (hostShared()) {
    EXPECT_NE(buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR, 0u);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(buffer.getInfo<CL_MEM_HOST_PTR>()) % (size_t(2) << 20), 0u);
  }
  roundTrip(buffer, count);
}

TEST(HostBackedBuffer, SmallBuffersAreTheDrivers) {
  cl::Buffer buffer = newDeviceBuffer(device(), CL_MEM_READ_ONLY, 4096);
  EXPECT_EQ(buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR, 0u);
  EXPECT_EQ(buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_READ_ONLY, cl_mem_flags(CL_MEM_READ_ONLY));
  roundTrip(buffer, 1024);
}

TEST(HostBackedBuffer, MemoryLivesAsLongAsAnyCopy) {
  const size_t count = (size_t(3) << 20) / sizeof(float);
  cl::Buffer copy;
  {
    cl::Buffer first = newDeviceBuffer(device(), CL_MEM_READ_WRITE, count * sizeof(float));
    roundTrip(first, count);
    copy = first;
  }
  roundTrip(copy, count);  // under the sanitizers a freed host pointer would be a use after free
}

}  // namespace
