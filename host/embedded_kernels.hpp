#pragma once
#include <vector>

namespace ssrcl::detail {

struct EmbeddedKernel {
  const char* name;    // file name under kernels/
  const char* source;  // its text
};

// Every kernels/*.cl file, in name order (generated at build time).
const std::vector<EmbeddedKernel>& embeddedKernels();

}  // namespace ssrcl::detail
