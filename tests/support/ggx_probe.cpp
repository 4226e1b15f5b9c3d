#include "support/ggx_probe.hpp"

#include "pipeline/opencl_c_on_host.hpp"

namespace ssrcl::test {

std::vector<glm::vec4> sampleGgxDirections(glm::vec3 o, float alpha, int count, std::uint32_t seed) {
  using namespace ssrcl::clc;
  std::vector<glm::vec4> out(std::size_t(count > 0 ? count : 0));
  const float3 ov = normalize(o);
  for (int i = 0; i < count; ++i) {  // as the tracer draws sample i of pixel 0
    const float3 h = ggx_sample_vndf(ov, alpha, sample_2d(0, 0, i, seed));
    const float3 l = 2.0f * dot(ov, h) * h - ov;
    out[i] = glm::vec4(l, ggx_vndf_reflection_pdf(ov, l, alpha));
  }
  return out;
}

}  // namespace ssrcl::test
