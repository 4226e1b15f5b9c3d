#include "support/ggx_probe.hpp"

#include <string>

#include "device_impl.hpp"
#include "embedded_kernels.hpp"

namespace ssrcl::test {
namespace {

// `count` reflected directions for the local view direction o (normal +Z) drawn exactly as the
// tracer draws them (sequence index = work-item), with their density. out[i] = (l.xyz, pdf).
const char* kProbeKernel = R"CL(
__kernel void ggx_sample_directions(float4 o, float alpha, uint seed, int count, __global float4* out) {
  int i = get_global_id(0);
  if (i >= count) return;
  float3 ov = normalize(o.xyz);
  float3 h = ggx_sample_vndf(ov, alpha, sample_2d(0, i, seed));
  float3 l = 2.0f * dot(ov, h) * h - ov;
  out[i] = (float4)(l, ggx_vndf_reflection_pdf(ov, l, alpha));
}
)CL";

}  // namespace

std::vector<glm::vec4> sampleGgxDirections(const Device& device, glm::vec3 o, float alpha, int count,
                                           std::uint32_t seed) {
  static_assert(sizeof(glm::vec4) == sizeof(cl_float4), "out[] is read straight into glm::vec4");
  std::vector<glm::vec4> out(std::size_t(count > 0 ? count : 0));
  if (out.empty()) return out;
  Device::Impl& d = detail::DeviceAccess::impl(device);
  // The library's own sampler sources (as the trace program lists them), plus the probe kernel.
  std::string source;
  for (const char* name : {"ssrcl_shared.h", "common.cl", "sequence.cl", "ggx.cl"})
    source += std::string(detail::embeddedKernel(name)) + "\n";
  cl::Program program(d.context, source + kProbeKernel);
  program.build({d.device}, "-cl-std=CL1.2");
  cl::Kernel kernel(program, "ggx_sample_directions");
  cl::Buffer buffer(d.context, CL_MEM_WRITE_ONLY, out.size() * sizeof(cl_float4));
  kernel.setArg(0, cl_float4{{o.x, o.y, o.z, 0.0f}});
  kernel.setArg(1, alpha);
  kernel.setArg(2, cl_uint(seed));
  kernel.setArg(3, cl_int(count));
  kernel.setArg(4, buffer);
  d.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(out.size()));
  d.queue.enqueueReadBuffer(buffer, CL_TRUE, 0, out.size() * sizeof(cl_float4), out.data());
  return out;
}

}  // namespace ssrcl::test
