#include "temporal_window.hpp"

#include <algorithm>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {

TemporalWindow::TemporalWindow(const GBufferInputOptions& input, std::vector<FrameJob> sequence, int k, uint32_t seed)
    : input_(input), sequence_(std::move(sequence)), k_(k), seed_(seed) {
  if (k < 0) throw Error(ErrorCode::InvalidArgument, "--temporal " + std::to_string(k) + ": must be 0 or more");
  for (size_t i = 0; i < sequence_.size(); ++i) byInput_[sequence_[i].input] = i;
}

size_t TemporalWindow::indexOf(const std::string& input) const {
  const auto it = byInput_.find(input);
  if (it == byInput_.end()) throw Error(ErrorCode::InvalidOperation, input + ": not a frame of the sequence");
  return it->second;
}

std::pair<size_t, size_t> TemporalWindow::span(size_t index) const {
  return {index > size_t(k_) ? index - size_t(k_) : 0, std::min(sequence_.size() - 1, index + size_t(k_))};
}

TemporalWindow::Traced TemporalWindow::trace(Pipeline& pipeline, NeighbourWindow* neighbours, size_t index,
                                             const Frame& frame, double& deviceMs) const {
  const std::string& input = sequence_[index].input;
  if (neighbours) neighbours->moveTo(pipeline, input);
  const uint32_t seed = pipeline.settings().seed;
  pipeline.settings().seed = frameSeed(seed_, index);
  setFrame(pipeline, frame);
  pipeline.commit();
  pipeline.execute();
  pipeline.settings().seed = seed;
  for (const auto& [stage, ms] : pipeline.stageTimes().ms) deviceMs += ms;
  Traced t;
  t.reflection = pipeline.output("reflection");  // copies: the pipeline reuses its outputs
  t.distance = pipeline.output("distance");
  t.view = pipeline.output("view");
  t.depth = frame.gbuffer.depth;
  t.normal = frame.gbuffer.normal;
  t.roughness = frame.gbuffer.roughness;
  t.camera = frame.camera;
  return t;
}

TemporalWindow::Pass TemporalWindow::blend(Pipeline& pipeline, NeighbourWindow* neighbours, const std::string& input,
                                           const Frame& frame) {
  const size_t centre = indexOf(input);
  const auto [first, last] = span(centre);
  for (auto it = traced_.begin(); it != traced_.end();)  // frames before the window are not needed again
    it = it->first < first ? traced_.erase(it) : std::next(it);
  Pass pass;
  for (size_t j = first; j <= last; ++j) {
    if (traced_.count(j)) continue;
    if (j == centre) {
      traced_[j] = trace(pipeline, neighbours, j, frame, pass.deviceMs);
      continue;
    }
    const FrameJob& job = sequence_[j];
    try {
      traced_[j] = trace(pipeline, neighbours, j, loadFrame(frameSource(input_, job)), pass.deviceMs);
    } catch (const Error& e) {
      throw Error(e.code(), "temporal neighbour " + job.input + ": " + e.what());
    }
  }
  std::vector<TemporalFrame> frames;
  for (size_t j = first; j <= last; ++j) {
    const Traced& t = traced_.at(j);
    frames.push_back(
        {&t.reflection, &t.distance, &t.depth, &t.normal, t.roughness.empty() ? nullptr : &t.roughness, t.camera});
  }
  TemporalSettings settings;
  settings.mirrorRoughness = pipeline.settings().mirrorRoughness;
  settings.constantRoughness = pipeline.settings().constantRoughness;
  const Traced& own = traced_.at(centre);
  pass.reflection = temporalBlend(frames, centre - first, settings);
  pass.distance = own.distance;
  pass.view = own.view;
  return pass;
}

std::vector<std::string> TemporalWindow::filesOf(const std::string& input) const {
  const size_t index = indexOf(input);
  const auto [first, last] = span(index);
  std::vector<std::string> out;
  for (size_t j = first; j <= last; ++j)
    if (j != index) out.push_back(sequence_[j].input);
  return out;
}

}  // namespace ssrcl::cli
