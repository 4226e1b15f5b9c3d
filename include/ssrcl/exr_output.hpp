#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {

// How the reflection pass is written (docs/outputs.md).
struct ReflectionExrOptions {
  // Channel prefix: "" writes R,G,B,A,distance; "refl" writes refl.R, ..., refl.distance.
  std::string layer;
  bool half = false;  // half-float pass channels (appended input channels keep their own type)
  // One of exrCompressionNames(); empty: defaultExrCompression(), or, when appending, the
  // appended file's.
  std::string compression;
  // Non-empty: the output is a copy of this single-part EXR (every channel with its type, every
  // attribute) with the pass's channels added; its data window must be the images'.
  std::string appendTo;
  // Non-empty: this EXR's pixel aspect ratio, screen window and chromaticities are carried over.
  std::string headerFrom;
  std::optional<ExrWindows> windows;  // data and display window; default: the images' size at 0,0
  // Written as OpenEXR's standard worldToCamera and worldToNDC (the camera of the display window).
  std::optional<Camera> camera;
  std::map<std::string, std::string> attributes;  // string attributes, e.g. "ssrcl/version"
  // Non-null: Pipeline::output("view") of a pass traced with auxiliary views, written as channels
  // `view` (the source of most of the found weight: 0 the frame, k its k-th view, -1 none) and
  // `view_share` (the fraction of A found in views), with the layer prefix. Read at the call only.
  const Image* view = nullptr;
};

// Writes the pass through a temporary in the same directory renamed over `path`, so a failure
// leaves any existing file untouched. Throws Error(IoError) when writing fails,
// Error(InvalidInput) when the file to append to cannot take the pass (naming it), and
// Error(InvalidArgument) for bad images or options.
void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance,
                        const ReflectionExrOptions& options);

// The values --compression takes, in OpenEXR's order.
const std::vector<std::string>& exrCompressionNames();

// The pass's compression when none is asked for (and nothing is appended to): "rle". Lossless,
// read by every OpenEXR reader; the pass's float channels are near noise that zlib barely
// shrinks, so ZIP made files only 4-7% smaller at ten times the time (docs/BENCHMARKS.md).
const std::string& defaultExrCompression();

// What an existing EXR says about how it was written, for resuming a batch.
struct ExrDescription {
  std::string compression;                            // one of exrCompressionNames()
  std::map<std::string, bool> channelIsHalf;          // every channel: true when stored as half
  std::map<std::string, std::string> stringAttributes;
};
// Throws Error(IoError) naming the file when it is not a readable EXR.
ExrDescription describeExr(const std::string& path);

}  // namespace ssrcl
