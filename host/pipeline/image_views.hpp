#pragma once
// Caller-owned images of any layout (ImageView) to and from the packed floats the device takes.
#include <vector>

#include "ssrcl/image.hpp"

namespace ssrcl::detail {

// A packed float view of an Image (the pipeline's own images and setImage(name, Image)).
ImageView viewOf(const Image& image);
// The view's pixels as packed floats: its own memory when it is already so laid out, else a
// converted copy in `staging`.
const float* packedFloats(const ImageView& view, std::vector<float>& staging);
// Writes an image into a caller's view of the same size and channel count.
void writeView(const Image& image, const ImageView& view);
// Empty: no memory, or no pixels.
bool emptyView(const ImageView& view);

}  // namespace ssrcl::detail
