#pragma once
// The depth samples of a deep OpenEXR file (scanline or tiled), read with OpenEXR's deep API:
// where along each pixel's ray the renderer found something, front (Z) and back (ZBack).
#include <cstdint>
#include <string>
#include <vector>

#include "ssrcl/image.hpp"

namespace ssrcl::detail {

struct DeepDepth {
  int width = 0, height = 0;        // the data window
  std::vector<uint32_t> counts;     // samples per pixel, row-major from the window's top row
  std::vector<uint64_t> first;      // each pixel's first sample in z / zBack (prefix sums of counts)
  std::vector<float> z, zBack;      // every sample, in the file's order; zBack = z where it has no ZBack
};

// Whether part 0 of `path` holds deep data. Throws Error(IoError) naming the file when it is not
// a readable OpenEXR file.
bool isDeepExr(const std::string& path);

// Reads Z (and ZBack) of part 0, level 0 of a tiled file. Throws Error(InvalidInput) naming the
// file when it is not deep or has no Z channel, Error(IoError) when it cannot be read.
DeepDepth readDeepDepth(const std::string& path);

// Each pixel's back-face depth from its samples: the back (ZBack) of its nearest sample, where that
// sample has a depth interval; 0 (unknown) where it has none, or no sample.
Image firstIntervalBack(const DeepDepth& deep);

}  // namespace ssrcl::detail
