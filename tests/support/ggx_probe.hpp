#pragma once
// The GGX sampler exactly as the kernels implement it: kernels/ggx.cl and kernels/sequence.cl
// compiled for the host (host/pipeline/opencl_c_on_host.hpp).
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

namespace ssrcl::test {

// `count` reflected directions for the local view direction o (normal +Z; o is normalized first)
// and GGX alpha, sequence indices 0..count-1 of `seed`: out[i] = (l.xyz, the pdf the tracer assigns).
std::vector<glm::vec4> sampleGgxDirections(glm::vec3 o, float alpha, int count, std::uint32_t seed);

}  // namespace ssrcl::test
