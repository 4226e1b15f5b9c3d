#pragma once
// Runs the GGX sampler exactly as the kernels implement it: the library's kernels/ggx.cl and
// kernels/sequence.cl with a probe kernel of the tests' own.
#include <cstdint>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "ssrcl/device.hpp"

namespace ssrcl::test {

// `count` reflected directions for the local view direction o (normal +Z; the kernel normalizes o)
// and GGX alpha, sequence indices 0..count-1 of `seed`: out[i] = (l.xyz, pdf the kernel assigns).
std::vector<glm::vec4> sampleGgxDirections(const Device& device, glm::vec3 o, float alpha, int count,
                                           std::uint32_t seed);

}  // namespace ssrcl::test
