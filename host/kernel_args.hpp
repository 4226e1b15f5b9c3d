#pragma once
#include <glm/mat4x4.hpp>

#include "opencl.hpp"

namespace ssrcl::detail {

// A glm matrix as the kernels take it: float16 in row-major order (glm is column-major).
inline cl_float16 toFloat16RowMajor(const glm::dmat4& m) {
  cl_float16 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.s[r * 4 + c] = static_cast<float>(m[c][r]);
  return out;
}

// Sets every argument of a kernel in order.
template <class... Args>
void setArgs(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (kernel.setArg(index++, args), ...);
}

inline size_t roundUp(size_t n, size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

}  // namespace ssrcl::detail
