#pragma once
// `ssrcl batch --temporal K`: each frame's pass blended (ssrcl::temporalBlend) with the passes of
// frames f-K..f+K (fewer at the shot's ends), each frame traced alone with its own seed: the
// batch's seed plus the frame's index in the sequence, so that the neighbours' noise is
// independent and averages out, and a frame's output depends on its window only (a shard or a
// resumed run traces the window's frames it does not own and equals the whole run bit for bit).
// Traced frames are kept while they stay in the window of the frames still to come.
#include <map>
#include <string>
#include <vector>

#include "batch_plan.hpp"
#include "gbuffer_input.hpp"
#include "neighbour_window.hpp"
#include "ssrcl/pipeline.hpp"
#include "ssrcl/temporal.hpp"

namespace ssrcl::cli {

class TemporalWindow {
 public:
  // `sequence`: every frame the batch planned, in order (all shards). Throws Error(InvalidArgument)
  // when K < 0.
  TemporalWindow(const GBufferInputOptions& input, std::vector<FrameJob> sequence, int k, uint32_t seed);

  // The seed frame `index` of the sequence is traced with.
  static uint32_t frameSeed(uint32_t seed, size_t index) { return seed + uint32_t(index); }

  struct Pass {
    Image reflection, distance, view;  // the pipeline's outputs; reflection blended
    double deviceMs = 0;               // device time of the traces this call ran
  };
  // The blended pass of the frame read from `input` (`frame`, already read: traced unless its
  // trace is kept). Other frames of its window are read and traced as needed, with `neighbours`'
  // views where given. Errors name the frame's file.
  Pass blend(Pipeline& pipeline, NeighbourWindow* neighbours, const std::string& input, const Frame& frame);

  // The files of frame `input`'s window but itself, in sequence order (its output's record).
  std::vector<std::string> filesOf(const std::string& input) const;

 private:
  struct Traced {
    Image reflection, distance, view, depth, normal, roughness;
    Camera camera;
  };
  size_t indexOf(const std::string& input) const;
  std::pair<size_t, size_t> span(size_t index) const;
  Traced trace(Pipeline& pipeline, NeighbourWindow* neighbours, size_t index, const Frame& frame,
               double& deviceMs) const;

  GBufferInputOptions input_;
  std::vector<FrameJob> sequence_;
  std::map<std::string, size_t> byInput_;
  int k_;
  uint32_t seed_;
  std::map<size_t, Traced> traced_;
};

}  // namespace ssrcl::cli
