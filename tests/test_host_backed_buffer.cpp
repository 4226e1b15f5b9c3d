// Device buffers (host/pipeline/host_backed_buffer.hpp): without a caller's memory they are the
// driver's and hold what is written to them. On a CPU device a frame's input image is read where it
// lies (no copy), and an output written where its image lies, when the memory is aligned as the
// device's buffers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <numeric>
#include <vector>

#include "pipeline/host_backed_buffer.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::detail;

ssrcl::Device::Impl& device() { return DeviceAccess::impl(ssrcl::test::sharedTestDevice()); }

bool hostShared() { return sharesHostMemory(device()); }

// Whether `buffer` is the memory at `host`.
bool usesHostMemory(const cl::Buffer& buffer, const void* host) {
  return (buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR) && buffer.getInfo<CL_MEM_HOST_PTR>() == host;
}

std::vector<float> readBack(const cl::Buffer& buffer, size_t count) {
  std::vector<float> out(count, -1.0f);
  device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
  return out;
}

void roundTrip(const cl::Buffer& buffer, size_t count) {
  std::vector<float> in(count), out(count, -1.0f);
  std::iota(in.begin(), in.end(), 0.5f);
  device().queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, count * sizeof(float), in.data());
  device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), out.data());
  EXPECT_EQ(in, out);
}

TEST(HostBackedBuffer, WithoutHostMemoryTheDriverAllocates) {
  for (const size_t bytes : {size_t(4096), size_t(5) << 20}) {  // small, and not a whole number of 2 MiB pages
    cl::Buffer buffer = newDeviceBuffer(device(), CL_MEM_READ_ONLY, bytes);
    EXPECT_EQ(buffer.getInfo<CL_MEM_SIZE>(), bytes);
    EXPECT_EQ(buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR, 0u);
    EXPECT_EQ(buffer.getInfo<CL_MEM_FLAGS>() & CL_MEM_READ_ONLY, cl_mem_flags(CL_MEM_READ_ONLY));
    roundTrip(buffer, bytes / sizeof(float));
  }
}

TEST(HostBackedBuffer, APlannedBufferIsTheCallersMemory) {
  const size_t count = (size_t(1) << 20) / sizeof(float), bytes = count * sizeof(float);
  const std::unique_ptr<float, decltype(&std::free)> image(static_cast<float*>(std::aligned_alloc(4096, bytes)),
                                                           &std::free);
  std::fill(image.get(), image.get() + count, 0.0f);
  std::vector<float> other(count);  // both memories outlive the buffers
  DeviceBuffers buffers;
  cl::Buffer output;
  buffers.add(output, bytes, CL_MEM_WRITE_ONLY);
  buffers.placeIn(output, image.get());
  buffers.allocate(device(), "test");
  EXPECT_EQ(usesHostMemory(output, image.get()), hostShared());
  device().queue.enqueueFillBuffer(output, 2.5f, 0, bytes);
  if (hostShared()) {  // written where the caller reads, once mapped
    void* mapped = device().queue.enqueueMapBuffer(output, CL_TRUE, CL_MAP_READ, 0, bytes);
    EXPECT_EQ(mapped, static_cast<void*>(image.get()));
    EXPECT_EQ(std::vector<float>(image.get(), image.get() + count), std::vector<float>(count, 2.5f));
    device().queue.enqueueUnmapMemObject(output, mapped);
    device().queue.finish();
  }
  // The same plan again keeps the buffer; another memory replaces it.
  buffers.add(output, bytes, CL_MEM_WRITE_ONLY);
  buffers.placeIn(output, image.get());
  EXPECT_FALSE(buffers.allocate(device(), "test"));
  buffers.add(output, bytes, CL_MEM_WRITE_ONLY);
  buffers.placeIn(output, other.data());
  EXPECT_TRUE(buffers.allocate(device(), "test"));
  EXPECT_FALSE(usesHostMemory(output, image.get()));
}

TEST(HostInput, AlignedPixelsAreReadWhereTheyLie) {
  const size_t count = (size_t(3) << 20) / sizeof(float), bytes = count * sizeof(float);
  const std::unique_ptr<float, decltype(&std::free)> pixels(static_cast<float*>(std::aligned_alloc(4096, bytes)),
                                                            &std::free);
  std::iota(pixels.get(), pixels.get() + count, 0.25f);
  const std::vector<float> expected(pixels.get(), pixels.get() + count);
  DeviceBuffers buffers;
  HostInput input;
  input.plan(device(), buffers, bytes);
  buffers.allocate(device(), "test");
  StageEvents events;
  const cl::Buffer& buffer = input.put(device().queue, pixels.get(), bytes, events);
  EXPECT_EQ(readBack(buffer, count), expected);
  if (hostShared()) {
    EXPECT_EQ(buffer.getInfo<CL_MEM_HOST_PTR>(), static_cast<void*>(pixels.get()));  // no copy
    EXPECT_LT(input.own().getInfo<CL_MEM_SIZE>(), bytes);  // nor a buffer of its own
    EXPECT_TRUE(events.empty());
  } else {
    EXPECT_EQ(buffer(), input.own()());
  }
}

TEST(HostInput, UnalignedPixelsAreCopied) {
  const size_t count = 1000, bytes = count * sizeof(float);
  std::vector<float> storage(count + 1);
  float* pixels = storage.data() + 1;  // 4 bytes off any buffer alignment a device asks
  std::iota(pixels, pixels + count, 3.0f);
  const std::vector<float> expected(pixels, pixels + count);
  DeviceBuffers buffers;
  HostInput input;
  input.plan(device(), buffers, bytes);
  buffers.allocate(device(), "test");
  StageEvents events;
  const cl::Buffer& buffer = input.put(device().queue, pixels, bytes, events);
  if (hostShared()) std::fill(pixels, pixels + count, 0.0f);  // the copy is the frame's: the caller may reuse its memory
  EXPECT_EQ(readBack(buffer, count), expected);
  EXPECT_NE(buffer.getInfo<CL_MEM_HOST_PTR>(), static_cast<void*>(pixels));
  EXPECT_EQ(input.put(device().queue, nullptr, bytes, events)(), input.own()());  // no image: its own, unwritten
}

}  // namespace
