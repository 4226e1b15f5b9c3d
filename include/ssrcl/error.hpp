#pragma once
#include <stdexcept>
#include <string>

namespace ssrcl {

// Typed failures, so callers (the CLI, batch jobs) can map them to exit codes and messages.
enum class ErrorCode {
  InvalidArgument,  // a parameter or image the caller gave is unusable
  InvalidOperation,  // a call out of order (execute before commit, an input resized and not committed)
  Cancelled,         // the progress monitor asked to stop
  InvalidInput,     // a file's content is wrong: missing channel, size mismatch, singular matrix
  IoError,          // a file cannot be read or written
  NoDevice,         // no OpenCL platform/device matches the request
  KernelBuild,      // OpenCL program failed to compile; buildLog() has the compiler's text
  OpenCL,           // any other OpenCL call failed; the message names the call and its code
  OutOfMemory,      // device or host allocation failed
};

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message, std::string buildLog = {})
      : std::runtime_error(message), code_(code), buildLog_(std::move(buildLog)) {}
  ErrorCode code() const noexcept { return code_; }
  const std::string& buildLog() const noexcept { return buildLog_; }

 private:
  ErrorCode code_;
  std::string buildLog_;
};

const char* errorCodeName(ErrorCode code) noexcept;

}  // namespace ssrcl
