#pragma once
#include <string>

#include "opencl.hpp"

namespace ssrcl::detail {

// Built programs' binaries kept on disk between processes, because a driver may run its compiler
// front end on every build from source even when its own cache holds the result (PoCL 3
// preprocesses each source to find it: about 0.3 s for a trace's programs, 25 ms from binaries).
// In $SSRCL_CACHE_DIR, else $XDG_CACHE_HOME/ssrcl, else $HOME/.cache/ssrcl; SSRCL_CACHE_DIR=""
// turns it off. A file holds the whole key (driver, device, options, source), so any change
// misses, and its binary's checksum; a file that cannot be read, is damaged, or that the driver
// refuses is a miss too, never an error.

// The program of `source` built with `options` for the context's only device, or a null program.
cl::Program cachedProgram(const cl::Context& context, const cl::Device& device, const std::string& source,
                          const std::string& options);

// Keeps the built `program` for cachedProgram; a cache that cannot be written is skipped.
void storeProgram(const cl::Program& program, const cl::Device& device, const std::string& source,
                  const std::string& options);

}  // namespace ssrcl::detail
