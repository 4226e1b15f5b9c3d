#pragma once
#include <chrono>
#include <cstddef>
#include <string>

namespace ssrcl::cli {

// The progress of a long run on one line of stderr: frames finished, frames/s and time left.
// Drawn only when stderr is a terminal, at most a few times a second; notes print above it.
class ProgressLine {
 public:
  ProgressLine(size_t total, bool enabled);
  void update(size_t finished, size_t failed);
  void note(const std::string& line);  // printed whether or not the line is drawn
  void finish();                       // erases the line

 private:
  void draw();
  void erase();

  size_t total_, finished_ = 0, failed_ = 0;
  bool enabled_, drawn_ = false;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace ssrcl::cli
