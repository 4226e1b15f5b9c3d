#pragma once
// The loaders read paths, so each fuzz input is written to one file that is rewritten per run:
// under /dev/shm (memory) where it exists, so the fuzzers are not disk-bound.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace ssrcl::fuzz {

inline std::string inputPath(const char* name) {
  const char* dir =
      access("/dev/shm", W_OK) == 0 ? "/dev/shm" : (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
  return std::string(dir) + "/ssrcl-fuzz-" + std::to_string(getpid()) + "-" + name;
}

inline void writeInput(const std::string& path, const uint8_t* data, size_t size) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
}

}  // namespace ssrcl::fuzz
