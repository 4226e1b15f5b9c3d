#include "progress_line.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace ssrcl::cli {
namespace {

std::string minutesSeconds(double seconds) {
  const long s = long(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

ProgressLine::ProgressLine(size_t total, bool enabled)
    : total_(total), enabled_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

void ProgressLine::update(size_t finished, size_t failed) {
  finished_ = finished;
  failed_ = failed;
  const auto now = std::chrono::steady_clock::now();
  if (now - lastDraw_ < std::chrono::milliseconds(200) && finished_ < total_) return;
  lastDraw_ = now;
  draw();
}

void ProgressLine::note(const std::string& line) {
  erase();
  std::cerr << line << "\n";
  draw();
}

void ProgressLine::finish() { erase(); }

void ProgressLine::draw() {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? finished_ / elapsed : 0.0;
  char text[160];
  std::snprintf(text, sizeof text, "\r\033[K%zu/%zu frames  %.2f frames/s  ETA %s", finished_, total_, rate,
                rate > 0 ? minutesSeconds((total_ - finished_) / rate).c_str() : "-");
  std::cerr << text;
  if (failed_) std::cerr << "  " << failed_ << " failed";
  std::cerr << std::flush;
  drawn_ = true;
}

void ProgressLine::erase() {
  if (!drawn_) return;
  std::cerr << "\r\033[K" << std::flush;
  drawn_ = false;
}

}  // namespace ssrcl::cli
