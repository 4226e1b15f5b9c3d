#pragma once
// What the per-stage units (host/*_stage.cpp) share: the frame's shape, the camera's matrices as
// the kernels take them, planned device buffers and profiling events.
#include <map>
#include <string>
#include <vector>

#include "device_impl.hpp"
#include "ssrcl/camera.hpp"
#include "ssrcl/pipeline.hpp"
#include "ssrcl_shared.h"

namespace ssrcl::detail {

using shared::EnvironmentParams;
using shared::FilterParams;
using shared::FrameConstants;
using shared::HzbLevel;
using shared::ResolveParams;
using shared::SetupParams;
using shared::ThicknessParams;
using shared::TraceParams;

// The frame every stage works on: its size, its SSRCL_TILE tiles and the pyramid levels (each
// ceil(previous / 2) down to 1x1, packed in one buffer).
struct FrameShape {
  int width = 0, height = 0, tilesX = 0, tilesY = 0;
  std::vector<HzbLevel> levels;

  FrameShape() = default;
  FrameShape(int w, int h);
  size_t pixels() const { return size_t(width) * height; }
  size_t pyramidTexels() const { return size_t(levels.back().offset) + 1; }
  cl::NDRange tiled2d() const;  // the frame in 2D SSRCL_TILE work-groups
};

// The block every stage's parameters begin with (kernels/ssrcl_shared.h): the camera as the
// kernels take it (row-major float matrices, clip planes as floats), the frame's size and tiles.
FrameConstants frameConstants(const FrameShape& frame, const Camera& camera, const TraceSettings& s);

// Device buffers planned by every stage before any is allocated: a frame the device cannot hold
// fails with the sizes named (checkDeviceMemory), not with an OpenCL status from whichever buffer
// meets the limit first. A buffer keeps its allocation while its planned size and flags stay the
// same, so a new frame of the same size reallocates nothing.
class DeviceBuffers {
 public:
  void add(cl::Buffer& buffer, size_t bytes, cl_mem_flags flags = CL_MEM_READ_WRITE);
  // The buffer planned as `buffer` is the caller's memory at `host` (of at least its bytes, outliving
  // it) where the device can work there (newDeviceBuffer); given once the plan is checked.
  void placeIn(const cl::Buffer& buffer, void* host);
  // Throws Error(OutOfMemory) naming `what` where the plan does not fit the device; else its bytes.
  size_t check(Device::Impl& device, const std::string& what) const;
  // Checks the plan against the device and (re)allocates what changed; clears the plan.
  // Returns whether anything was (re)allocated.
  bool allocate(Device::Impl& device, const std::string& what);
  size_t bytes() const { return bytes_; }  // of the last allocated plan

 private:
  struct Planned {
    cl::Buffer* buffer;
    size_t bytes;
    cl_mem_flags flags;
    void* host;
    bool operator==(const Planned& o) const { return bytes == o.bytes && flags == o.flags && host == o.host; }
  };
  std::vector<Planned> planned_;
  std::map<const cl::Buffer*, Planned> allocated_;
  size_t bytes_ = 0;
};

// Profiling events of one execute, by StageTimes name ("setup", "trace", ...).
using StageEvents = std::map<std::string, std::vector<cl::Event>>;
cl::Event* newEvent(StageEvents& events, const std::string& stage);
double eventMs(const cl::Event& e);

// Checks that the kernel's arguments from `first` on are `count` arguments named `names`
// (comma-separated, as the kernel declares them; programs are built with -cl-kernel-arg-info), so
// a host binding out of step with its kernel fails at commit, naming both, instead of tracing
// with buffers in the wrong places. Throws Error(InvalidOperation). Names are not checked on a
// driver that keeps no argument information.
void checkKernelArgs(const cl::Kernel& kernel, cl_uint first, const char* names, size_t count);

// Binds a kernel's arguments from `first` on, in order, to the parameters `names` (checkKernelArgs).
template <class... Args>
void bindArgs(cl::Kernel& kernel, cl_uint first, const char* names, const Args&... args) {
  checkKernelArgs(kernel, first, names, sizeof...(args));
  cl_uint index = first;
  (kernel.setArg(index++, args), ...);
}

// A kernel's arguments from `first` on as the host binds them (bindArgs), and where one of them
// lies by name: an argument set again each frame (the frame's own input passes) is set at
// args["depth_in"], so it stays in step with the checked binding. An unknown name throws
// Error(InvalidOperation).
struct KernelArgList {
  cl_uint first;
  const char* names;
  cl_uint operator[](const std::string& name) const;
};

template <class... Args>
void bindArgs(cl::Kernel& kernel, const KernelArgList& list, const Args&... args) {
  bindArgs(kernel, list.first, list.names, args...);
}

size_t roundUp(size_t n, size_t multiple);
void toRowMajor(const glm::dmat4& m, float out[16]);
// The SSRCL_ROUGHNESS_MAPPING define of programs that map roughness to GGX alpha.
std::string roughnessMappingDefine(RoughnessMapping m);
// Of each similar neighbour's rays the resolve takes one share in this many (a pixel's own rays
// all), neighbouring pixels different shares: 4 when the edge-aware filter follows, whose average
// over neighbouring pixels then meets more distinct rays than the reuse gave each (corpus, high:
// +0.2 dB, p99 error -0.25% of the peak, 112 taps instead of 400); 1 without
// (medium lost 0.85 dB, docs/BENCHMARKS.md).
int resolveRayStride(const TraceSettings& s);
// Rays a glossy pixel's estimate stands on, which sets each ray's share of the lobe (the cone of
// its prefiltered hit): every ray of its reuse window. With the filter the resolve takes a share
// of each neighbour's, but neighbouring pixels take different shares and the filter averages them
// back together; counting only the taps (28 of medium's 100) read hits a mip coarser and darkened
// the pass: night_street's mean signed error 0.0102 under the full-resolution pass's instead of
// 0.0035 (tests/test_corpus.cpp, docs/BENCHMARKS.md "Speckle").
int resolvedRays(const TraceSettings& s);

}  // namespace ssrcl::detail
