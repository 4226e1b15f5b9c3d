#include "temporal_window.hpp"

#include <algorithm>

namespace ssrcl::cli {

TemporalWindow::TemporalWindow(std::vector<FrameJob> sequence, int k, uint32_t seed)
    : sequence_(std::move(sequence)), k_(k), seed_(seed) {
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

std::vector<size_t> TemporalWindow::plan(const std::vector<std::string>& inputs) {
  traced_.clear();
  waiting_.clear();
  for (const std::string& input : inputs) {
    const auto [first, last] = span(indexOf(input));
    for (size_t j = first; j <= last; ++j) ++waiting_[j];
  }
  std::vector<size_t> order;
  for (const auto& [j, count] : waiting_) order.push_back(j);
  return order;
}

double TemporalWindow::trace(Pipeline& pipeline, NeighbourWindow* neighbours, size_t index, const Frame& frame) {
  if (!waiting_.count(index)) return 0;  // every blend that wanted it failed already
  const std::string& input = sequence_[index].input;
  if (neighbours) neighbours->moveTo(pipeline, input);
  const uint32_t seed = pipeline.settings().seed;
  pipeline.settings().seed = frameSeed(seed_, index);
  setFrame(pipeline, frame);
  pipeline.commit();
  pipeline.execute();
  pipeline.settings().seed = seed;
  double deviceMs = 0;
  for (const auto& [stage, ms] : pipeline.stageTimes().ms) deviceMs += ms;
  Traced& t = traced_[index];
  t.reflection = pipeline.output("reflection");  // copies: the pipeline reuses its outputs
  t.distance = pipeline.output("distance");
  t.view = pipeline.output("view");
  t.depth = frame.gbuffer.depth;
  t.normal = frame.gbuffer.normal;
  t.roughness = frame.gbuffer.roughness;
  t.camera = frame.camera;
  return deviceMs;
}

void TemporalWindow::fail(size_t index, const Error& error) {
  if (waiting_.count(index)) traced_.insert_or_assign(index, Traced{{}, {}, {}, {}, {}, {}, {}, error, nullptr});
}

bool TemporalWindow::ready(const std::string& input) const {
  const auto [first, last] = span(indexOf(input));
  for (size_t j = first; j <= last; ++j)
    if (!traced_.count(j)) return false;
  return true;
}

void TemporalWindow::releaseWindow(size_t index) {
  const auto [first, last] = span(index);
  for (size_t j = first; j <= last; ++j) {
    const auto it = waiting_.find(j);
    if (it == waiting_.end() || --it->second > 0) continue;
    waiting_.erase(it);
    traced_.erase(j);
  }
}

void TemporalWindow::release(const std::string& input) { releaseWindow(indexOf(input)); }

TemporalWindow::Pass TemporalWindow::blend(Pipeline& pipeline, const std::string& input) {
  const size_t centre = indexOf(input);
  const auto [first, last] = span(centre);
  std::vector<TemporalFrame> frames;
  for (size_t j = first; j <= last; ++j) {
    const Traced& t = traced_.at(j);
    if (t.failure) {
      const Error e = *t.failure;
      releaseWindow(centre);
      throw Error(e.code(), "temporal neighbour " + sequence_[j].input + ": " + e.what());
    }
    frames.push_back({&t.reflection, &t.distance, &t.depth, &t.normal, t.roughness.empty() ? nullptr : &t.roughness,
                      t.camera, t.statistics});
  }
  TemporalSettings settings;
  settings.mirrorRoughness = pipeline.settings().mirrorRoughness;
  settings.constantRoughness = pipeline.settings().constantRoughness;
  const Traced& own = traced_.at(centre);
  Pass pass;
  try {
    // Each frame's statistics once, kept with it for the other windows that hold it.
    for (size_t j = first; j <= last; ++j) {
      Traced& t = traced_.at(j);
      if (!t.statistics) frames[j - first].statistics = t.statistics = temporalFrameStatistics(frames[j - first]);
    }
    pass = {temporalBlend(frames, centre - first, settings), own.distance, own.view};
  } catch (...) {
    releaseWindow(centre);
    throw;
  }
  releaseWindow(centre);
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
