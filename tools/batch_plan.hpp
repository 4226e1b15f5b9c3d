#pragma once
#include <optional>
#include <string>
#include <vector>

namespace ssrcl::cli {

// One frame of a batch: where its G-buffer, camera and reflection pass are.
struct FrameJob {
  std::string name;          // the frame number, or the input's stem when it has none
  std::optional<int> frame;  // set for frame patterns
  std::string input, camera, output;
  std::string backDepth;     // its back-face depth file; empty: the frame's own BackFaces layer, if any
};

// What `ssrcl batch` was asked to do, as typed.
struct BatchRequest {
  std::vector<std::string> inputs;  // one frame pattern, one glob, or files
  std::string output;               // "refl/sh010.####.exr", "refl/{stem}.refl.exr", or a directory ("refl/")
  std::string frames;               // a range for a frame pattern; empty: the frames on disk
  std::string camera;               // empty: <stem>.camera.json beside each frame; else one file, or a pattern
  std::string backDepth;            // empty: none (each frame's own BackFaces layer); else a pattern or template
};

// Every frame of the request, in frame (or path) order, with its paths resolved. Throws
// Error(InvalidArgument) when the request cannot name a distinct output per frame, an output
// would replace an input, or it finds no frame.
std::vector<FrameJob> planBatch(const BatchRequest& request);

// Removes the hidden temporary files an output write left behind when its process was killed
// (writeReflectionExr writes ".<name>.tmp.<n>.exr" beside the output, then renames it).
void removeStaleTemporaries(const std::vector<const FrameJob*>& jobs);

}  // namespace ssrcl::cli
