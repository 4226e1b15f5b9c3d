#pragma once
#include "ssrcl/error.hpp"

namespace ssrcl::cli {

// Exit codes scripts can rely on (documented in docs/cli.md, "Exit codes").
constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;  // a bug: please report
constexpr int kExitUsage = 2;     // bad command line, or unusable input file/camera/parameter
constexpr int kExitDevice = 3;    // no OpenCL device, kernel build failure, device out of memory
constexpr int kExitOutput = 4;    // the output could not be written (nothing was overwritten)

inline int exitCodeFor(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidArgument:
    case ErrorCode::InvalidInput:
    case ErrorCode::IoError:
      return kExitUsage;
    case ErrorCode::NoDevice:
    case ErrorCode::KernelBuild:
    case ErrorCode::OpenCL:
    case ErrorCode::OutOfMemory:
      return kExitDevice;
    case ErrorCode::InvalidOperation:  // the library used out of order: a bug here
    case ErrorCode::Cancelled:         // nothing here cancels
      return kExitInternal;
  }
  return kExitInternal;
}

}  // namespace ssrcl::cli
