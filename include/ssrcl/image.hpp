#pragma once
#include <cstddef>
#include <vector>

namespace ssrcl {

// Planar-interleaved float image: pixel (x, y), channel c at data[(y * width + x) * channels + c],
// row 0 at the top as in EXR.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> data;

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), data(std::size_t(w) * h * c, 0.0f) {}
  float& at(int x, int y, int c) { return data[(std::size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return data[(std::size_t(y) * width + x) * channels + c]; }
  bool empty() const { return data.empty(); }
};

}  // namespace ssrcl
