#include "support/ggx_probe.hpp"

#include "device_impl.hpp"

namespace ssrcl::test {

std::vector<glm::vec4> sampleGgxDirections(const Device& device, glm::vec3 o, float alpha, int count,
                                           std::uint32_t seed) {
  static_assert(sizeof(glm::vec4) == sizeof(cl_float4), "out[] is read straight into glm::vec4");
  std::vector<glm::vec4> out(std::size_t(count > 0 ? count : 0));
  if (out.empty()) return out;
  Device::Impl& d = device.impl();
  cl::Kernel kernel(d.program(), "ggx_sample_directions");
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
