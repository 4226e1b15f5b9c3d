#pragma once
// `ssrcl batch --neighbours K`: frames of the shot around each frame as its auxiliary views
// (ViewTime::Other: static geometry only), K on each side reaching `--neighbour-reach` frames out.
// Frames far apart show what the frame does not (what lies past its edges as the camera moves),
// where adjacent ones add little. View k is always the window's k-th frame in sequence order, so
// a frame's views are the same whatever frames went before it (shards, resumed runs); moving from
// one frame to the next replaces the views whose frame changed, and a frame read once serves the
// windows that follow while they want it (read again where a later window wants it back).
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "batch_plan.hpp"
#include "gbuffer_input.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// How a batch reads job's frame: its camera file, its sidecar, or (no sidecar) its EXR header.
FrameSource frameSource(const GBufferInputOptions& input, const FrameJob& job);

class NeighbourWindow {
 public:
  // `sequence`: every frame the batch planned, in order (all shards, frames skipped or not).
  // Neighbours take the pipeline's views from `firstView` on (after the static --view ones).
  // `reach`: how far (in frames) the farthest neighbour on each side is. Throws
  // Error(InvalidArgument) when K < 0, reach < K, the sequence has fewer than 2K + 1 frames, or
  // firstView + 2K views exceed the pipeline's maximum.
  NeighbourWindow(const GBufferInputOptions& input, std::vector<FrameJob> sequence, int k, int reach, int firstView);

  // The sequence indices of frame `index`'s 2K neighbours, in order: for j = 1..K the frames
  // round(reach j / K) before and after it (at least j); where the shot has none on one side, as
  // far out on the other; a frame taken already gives way to the nearest free one.
  static std::vector<size_t> members(size_t index, size_t count, int k, int reach);

  // Makes the pipeline's neighbour views those of the frame read from `input`, view k its window's
  // k-th frame (read with the frames' channel options and camera rules); views that show that
  // frame already stay as they are. Errors name the neighbour's file.
  void moveTo(Pipeline& pipeline, const std::string& input);
  // Keeps the G-buffer of the frame read from `input`, just traced, for its successors' windows.
  void keep(const std::string& input, Frame&& frame);
  // The neighbours' files in view order, which is sequence order (for the output's record).
  std::vector<std::string> files() const;
  // The files of the frame read from `input`'s neighbours, in sequence order (what resuming
  // compares with an output's record).
  std::vector<std::string> filesOf(const std::string& input) const;

 private:
  size_t indexOf(const std::string& input) const;
  // The window of the frame after `index` (its own at the sequence's end): what a frame traced in
  // order is kept for.
  std::vector<size_t> windowAfter(size_t index) const;

  GBufferInputOptions input_;  // as views are read
  std::vector<FrameJob> sequence_;
  std::map<std::string, size_t> byInput_;
  int k_, reach_, firstView_;
  std::map<size_t, std::shared_ptr<const Frame>> loaded_;  // frames of the current window
  std::vector<std::optional<size_t>> slots_;               // the sequence frame each view shows
  std::set<size_t> checked_;                               // frames whose conventions were checked
};

}  // namespace ssrcl::cli
