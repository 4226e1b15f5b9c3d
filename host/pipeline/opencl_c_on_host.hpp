#pragma once
// The kernels' pure-math files (kernels/ggx.cl, kernels/sequence.cl) compiled as C++, with glm
// standing in for OpenCL C's vector types and built-ins, in namespace ssrcl::clc: the host calls
// the very GGX sampler, pdf and sample sequence the tracer calls (pbrt's way), e.g. in the tests.
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "ssrcl_shared.h"

namespace ssrcl::clc {

using float2 = glm::vec2;
using float3 = glm::vec3;
using uint = unsigned int;
using glm::cross;
using glm::dot;
using glm::length;
using std::floor;
using std::fmax;
using std::sqrt;
inline float rsqrt(float x) { return 1.0f / std::sqrt(x); }
inline float2 floor(float2 v) { return glm::floor(v); }
inline float sincos(float x, float* cos_x) {
  *cos_x = std::cos(x);
  return std::sin(x);
}
// As OpenCL C's: a zero vector stays zero (glm's would be NaN).
inline float3 normalize(float3 v) {
  const float l = glm::length(v);
  return l > 0.0f ? v / l : v;
}

#define SSRCL_FLOAT2(x, y) ::ssrcl::clc::float2(x, y)
#define SSRCL_FLOAT3(x, y, z) ::ssrcl::clc::float3(x, y, z)
#include "ggx.cl"
#include "sequence.cl"
#undef SSRCL_FLOAT2
#undef SSRCL_FLOAT3

}  // namespace ssrcl::clc
