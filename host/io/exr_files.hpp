#pragma once
#include <memory>
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// The EXR files one frame is read from, each opened and its headers read once however many
// questions are asked of it (which material passes it holds, then its passes): loadFrame asks
// both of the same file.
class ExrFiles {
 public:
  ExrFiles();
  ~ExrFiles();
  ExrFiles(const ExrFiles&) = delete;
  ExrFiles& operator=(const ExrFiles&) = delete;

  // holdsChannels(file, names), the file opened here once.
  bool holds(const std::string& file, const std::string& names);

  struct Opened;  // the files by path (host/io/exr_gbuffer.cpp)
  Opened& opened() { return *opened_; }

 private:
  std::unique_ptr<Opened> opened_;
};

// loadGBuffer(source), its files opened through `files`.
GBuffer loadGBuffer(const GBufferSource& source, ExrFiles& files);

}  // namespace ssrcl::detail
