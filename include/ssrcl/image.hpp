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

enum class PixelFormat { Float, Half };  // 32-bit or 16-bit (IEEE binary16) floats per channel

// A caller-owned image of any layout: pixel (x, y), channel c at
// data + y * rowStride + x * pixelStride + c * (2 or 4 bytes). Strides are in bytes; 0 means
// packed (pixelStride = channels * channel size, rowStride = width * pixelStride).
struct ImageView {
  void* data = nullptr;
  PixelFormat format = PixelFormat::Float;
  int width = 0, height = 0, channels = 0;
  std::size_t pixelStride = 0, rowStride = 0;

  ImageView() = default;
  ImageView(void* d, PixelFormat f, int w, int h, int c, std::size_t pixel = 0, std::size_t row = 0)
      : data(d), format(f), width(w), height(h), channels(c), pixelStride(pixel), rowStride(row) {}
  ImageView(const float* d, int w, int h, int c)  // packed floats (read-only use)
      : ImageView(const_cast<float*>(d), PixelFormat::Float, w, h, c) {}
};

}  // namespace ssrcl
