#pragma once
// The one place that configures the OpenCL C++ bindings for the library.
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>
#include <string>

#include "ssrcl/error.hpp"

namespace ssrcl::detail {

// "CL_OUT_OF_RESOURCES" for -5, etc.
const char* clErrorName(cl_int code);

// Converts an OpenCL binding exception into a typed ssrcl::Error naming the failed call.
[[noreturn]] void rethrowClError(const cl::Error& e, const std::string& context);

}  // namespace ssrcl::detail
