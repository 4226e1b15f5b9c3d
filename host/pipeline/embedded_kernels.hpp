#pragma once
#include <string>
#include <vector>

namespace ssrcl::detail {

struct EmbeddedKernel {
  const char* name;    // file name under kernels/
  const char* source;  // its text
};

// Every kernels/*.cl and *.h file, in name order (generated at build time).
const std::vector<EmbeddedKernel>& embeddedKernels();

// The text of kernels/<name>; throws std::logic_error for a name that is not embedded.
const char* embeddedKernel(const std::string& name);

}  // namespace ssrcl::detail
