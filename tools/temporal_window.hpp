#pragma once
// `ssrcl batch --temporal K`: each frame's pass blended (ssrcl::temporalBlend) with the passes of
// frames f-K..f+K (fewer at the shot's ends), each frame traced alone with its own seed: the
// batch's seed plus the frame's index in the sequence, so that the neighbours' noise is
// independent and averages out, and a frame's output depends on its window only (a shard or a
// resumed run traces the window's frames it does not own and equals the whole run bit for bit).
// The batch reads and traces every frame of the windows once, in any order (plan()); a traced
// frame is kept while a planned frame's window that still waits for its blend holds it.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "batch_plan.hpp"
#include "neighbour_window.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/pipeline.hpp"
#include "ssrcl/temporal.hpp"

namespace ssrcl::cli {

class TemporalWindow {
 public:
  // `sequence`: every frame the batch planned, in order (all shards). Throws Error(InvalidArgument)
  // when K < 0.
  TemporalWindow(std::vector<FrameJob> sequence, int k, uint32_t seed);

  // The seed frame `index` of the sequence is traced with.
  static uint32_t frameSeed(uint32_t seed, size_t index) { return seed + uint32_t(index); }

  // Plans the blends of the frames read from `inputs` (those to write): returns the sequence
  // indices of the frames their windows hold, ascending, each once: what is to be read and traced.
  std::vector<size_t> plan(const std::vector<std::string>& inputs);
  const FrameJob& job(size_t index) const { return sequence_[index]; }
  size_t indexOf(const std::string& input) const;

  // Traces frame `index` of the sequence, read as `frame`, with `neighbours`' views where given,
  // and keeps what the blends need. Returns the trace's device time in ms.
  double trace(Pipeline& pipeline, NeighbourWindow* neighbours, size_t index, const Frame& frame);
  // Frame `index` could not be read or traced: the blends whose window holds it fail naming it.
  void fail(size_t index, const Error& error);

  // Whether every frame of the planned frame `input`'s window is traced (or failed).
  bool ready(const std::string& input) const;
  struct Pass {
    Image reflection, distance, view;  // the frame's own outputs; reflection blended
  };
  // The pass of the planned frame `input` (ready); releases its window's frames. Throws (naming
  // the neighbour's file) when a frame of its window failed.
  Pass blend(Pipeline& pipeline, const std::string& input);
  // The planned frame `input` will not be blended (it failed): releases its window's frames.
  void release(const std::string& input);
  // The files of frame `input`'s window but itself, in sequence order (its output's record).
  std::vector<std::string> filesOf(const std::string& input) const;

 private:
  struct Traced {
    Image reflection, distance, view, depth, normal, roughness;
    Camera camera;
    std::optional<Error> failure;  // read or traced it could not be
    std::shared_ptr<const TemporalFrameStatistics> statistics;  // at its first blend, for the rest
  };
  std::pair<size_t, size_t> span(size_t index) const;
  // One planned blend fewer waits for each frame of `index`'s window; frames none waits for go.
  void releaseWindow(size_t index);

  std::vector<FrameJob> sequence_;
  std::map<std::string, size_t> byInput_;
  int k_;
  uint32_t seed_;
  std::map<size_t, Traced> traced_;
  std::map<size_t, int> waiting_;  // sequence index -> planned blends still to use it
};

}  // namespace ssrcl::cli
