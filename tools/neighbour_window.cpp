#include "neighbour_window.hpp"

#include <algorithm>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {

FrameSource frameSource(const GBufferInputOptions& input, const FrameJob& job) {
  FrameSource s = input.sourceFor(job.input, job.camera == sidecarCameraPath(job.input) ? "" : job.camera);
  s.backDepthFile = job.backDepth;
  return s;
}

NeighbourWindow::NeighbourWindow(const GBufferInputOptions& input, std::vector<FrameJob> sequence, int k, int firstView)
    : input_(viewInputOptions(input)), sequence_(std::move(sequence)), k_(k), firstView_(firstView) {
  if (k < 0) throw Error(ErrorCode::InvalidArgument, "--neighbours " + std::to_string(k) + ": must be 0 or more");
  // The view count first, in 64 bits: 2K + 1 overflows int for a huge K.
  if (firstView + 2LL * k > Pipeline::kMaxViews)
    throw Error(ErrorCode::InvalidArgument, "--neighbours " + std::to_string(k) + " with " + std::to_string(firstView) +
                                                " --view: " + std::to_string(firstView + 2LL * k) + " views, at most " +
                                                std::to_string(Pipeline::kMaxViews));
  if (sequence_.size() < size_t(2 * k + 1))
    throw Error(ErrorCode::InvalidArgument, "--neighbours " + std::to_string(k) + " needs at least " +
                                                std::to_string(2 * k + 1) + " frames in the sequence, it has " +
                                                std::to_string(sequence_.size()));
  for (size_t i = 0; i < sequence_.size(); ++i) byInput_[sequence_[i].input] = i;
  slots_.resize(size_t(2 * k));
}

std::pair<size_t, size_t> NeighbourWindow::span(size_t index, size_t count, int k) {
  const size_t width = size_t(2 * k);
  const size_t first = std::min(index > size_t(k) ? index - size_t(k) : 0, count - 1 - width);
  return {first, first + width};
}

size_t NeighbourWindow::indexOf(const std::string& input) const {
  const auto it = byInput_.find(input);
  if (it == byInput_.end()) throw Error(ErrorCode::InvalidOperation, input + ": not a frame of the sequence");
  return it->second;
}

void NeighbourWindow::moveTo(Pipeline& pipeline, const std::string& input) {
  const size_t index = indexOf(input);
  const std::pair<size_t, size_t> window = span(index, sequence_.size(), k_);
  const size_t first = window.first, last = window.second;
  const auto wanted = [&](size_t j) { return j >= first && j <= last && j != index; };
  for (auto& slot : slots_)
    if (slot && !wanted(*slot)) slot.reset();
  for (auto it = loaded_.begin(); it != loaded_.end();)
    it = it->first >= first && it->first <= last ? std::next(it) : loaded_.erase(it);
  for (size_t j = first; j <= last; ++j) {
    if (!wanted(j) || std::find(slots_.begin(), slots_.end(), j) != slots_.end()) continue;
    const FrameJob& job = sequence_[j];
    std::shared_ptr<const Frame>& frame = loaded_[j];
    if (!frame) try {
        frame = std::make_shared<const Frame>(
            loadFrame(frameSource(input_, job)));
      } catch (const Error& e) {
        loaded_.erase(j);
        throw Error(e.code(), "neighbour " + job.input + ": " + e.what());
      }
    const size_t slot = size_t(std::find(slots_.begin(), slots_.end(), std::nullopt) - slots_.begin());
    slots_[slot] = j;
    pipeline.setView(firstView_ + int(slot), frame->gbuffer, frame->camera, job.input, ViewTime::Other);
  }
}

void NeighbourWindow::keep(const std::string& input, Frame&& frame) {
  loaded_[indexOf(input)] = std::make_shared<const Frame>(std::move(frame));
}

std::vector<std::string> NeighbourWindow::filesOf(const std::string& input) const {
  const size_t index = indexOf(input);
  const auto [first, last] = span(index, sequence_.size(), k_);
  std::vector<std::string> out;
  for (size_t j = first; j <= last; ++j)
    if (j != index) out.push_back(sequence_[j].input);
  return out;
}

std::vector<std::string> NeighbourWindow::files() const {
  std::vector<std::string> out;
  for (const auto& slot : slots_)
    if (slot) out.push_back(sequence_[*slot].input);
  return out;
}

}  // namespace ssrcl::cli
