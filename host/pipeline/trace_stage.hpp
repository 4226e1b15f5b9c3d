#pragma once
// Ray generation and tracing (kernels/trace.cl): rays for the listed pixels, traced through the
// depth buffer by the tracer the settings name (a program variant), shaded at their hits. Plans the
// ray records the resolve reads, and owns the optional base/specular passes and the counting mode's
// counters, and with material passes each pixel's F0 and the table of the specular lobe's albedo
// E that shades hits on glossy pixels. Samples are traced in batches when all of them would not
// fit the record budget.
#include "frame_resources.hpp"
#include "host_backed_buffer.hpp"

namespace ssrcl::detail {

// The SSRCL_TRACER define of programs that trace.
std::string tracerDefine(Tracer t);

class TraceStage {
 public:
  // With views, the trace also writes each ray's state (rayState) for the view stage. With
  // `materials` (and base): hits on glossy pixels are shaded with their F0 (kernels/trace.cl).
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s, bool hasBase, bool materials, bool views,
                 bool backDepth);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  // Uploads base and specular, and F0 with materials (packed floats, when set; F0 in [0, 1]), and
  // clears the counters (counting mode).
  void upload(cl::CommandQueue& q, const float* base, const float* specular, const float* f0, StageEvents& events);
  // One batch: samples [params.first_sample, + batchSize()) of the `listed` pixels.
  void enqueue(cl::CommandQueue& q, const TraceParams& params, StageEvents& events);
  // Counting mode: texel reads and the iteration histogram into `times` (waits for the queue).
  void readWork(cl::CommandQueue& q, StageTimes& times);
  static TraceParams params(const FrameConstants& constants, const FrameShape& frame, const TraceSettings& s,
                            bool hasBase);

  int batchSize() const { return batch_; }  // samples per pixel in the ray records

 private:
  bool hasBase_ = false, materials_ = false, counting_ = false, views_ = false;
  int samples_ = 1;  // rays a pixel (TraceSettings::samplesPerPixel)
  int batch_ = 1;
  Device::Impl* device_ = nullptr;
  FrameShape frame_;
  cl::Kernel kernel_;
  HostInput baseIn_, specularIn_, f0In_;
  cl::Buffer albedoTable_, workCounters_;
};

}  // namespace ssrcl::detail
