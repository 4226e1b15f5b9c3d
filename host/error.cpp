#include "ssrcl/error.hpp"

namespace ssrcl {

const char* errorCodeName(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::InvalidArgument:
      return "invalid argument";
    case ErrorCode::InvalidOperation:
      return "invalid operation";
    case ErrorCode::Cancelled:
      return "cancelled";
    case ErrorCode::InvalidInput:
      return "invalid input";
    case ErrorCode::IoError:
      return "I/O error";
    case ErrorCode::NoDevice:
      return "no device";
    case ErrorCode::KernelBuild:
      return "kernel build failed";
    case ErrorCode::OpenCL:
      return "OpenCL error";
    case ErrorCode::OutOfMemory:
      return "out of memory";
  }
  return "unknown error";
}

}  // namespace ssrcl
