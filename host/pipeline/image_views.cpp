#include "image_views.hpp"

#include <Imath/half.h>

#include <cstring>

namespace ssrcl::detail {
namespace {

size_t channelBytes(const ImageView& v) { return v.format == PixelFormat::Half ? 2 : 4; }
size_t pixelStride(const ImageView& v) { return v.pixelStride ? v.pixelStride : v.channels * channelBytes(v); }
size_t rowStride(const ImageView& v) { return v.rowStride ? v.rowStride : v.width * pixelStride(v); }

// Calls f(address of channel c of pixel (x, y), packed index) for every channel of every pixel.
template <class F>
void forEachChannel(const ImageView& v, F f) {
  auto* base = static_cast<unsigned char*>(v.data);
  size_t i = 0;
  for (int y = 0; y < v.height; ++y)
    for (int x = 0; x < v.width; ++x)
      for (int c = 0; c < v.channels; ++c, ++i) f(base + y * rowStride(v) + x * pixelStride(v) + c * channelBytes(v), i);
}

}  // namespace

ImageView viewOf(const Image& image) {
  return ImageView(image.data.data(), image.width, image.height, image.channels);
}

bool emptyView(const ImageView& view) { return !view.data || view.width <= 0 || view.height <= 0 || view.channels <= 0; }

const float* packedFloats(const ImageView& view, std::vector<float>& staging) {
  if (view.format == PixelFormat::Float && pixelStride(view) == view.channels * sizeof(float) &&
      rowStride(view) == view.width * pixelStride(view))
    return static_cast<const float*>(view.data);
  staging.resize(size_t(view.width) * view.height * view.channels);
  forEachChannel(view, [&](const unsigned char* p, size_t i) {
    if (view.format == PixelFormat::Half) {
      Imath::half h;
      std::memcpy(&h, p, 2);
      staging[i] = float(h);
    } else {
      std::memcpy(&staging[i], p, 4);
    }
  });
  return staging.data();
}

void writeView(const Image& image, const ImageView& view) {
  forEachChannel(view, [&](unsigned char* p, size_t i) {
    if (view.format == PixelFormat::Half) {
      const Imath::half h(image.data[i]);
      std::memcpy(p, &h, 2);
    } else {
      std::memcpy(p, &image.data[i], 4);
    }
  });
}

}  // namespace ssrcl::detail
