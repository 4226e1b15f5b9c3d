#include "neighbour_window.hpp"

#include <algorithm>
#include <cmath>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {

FrameSource frameSource(const GBufferInputOptions& input, const FrameJob& job) {
  FrameSource s = input.sourceFor(job.input, job.camera == sidecarCameraPath(job.input) ? "" : job.camera);
  s.backDepthFile = job.backDepth;
  return s;
}

NeighbourWindow::NeighbourWindow(const GBufferInputOptions& input, std::vector<FrameJob> sequence, int k, int reach,
                                 int firstView)
    : input_(viewInputOptions(input)), sequence_(std::move(sequence)), k_(k), reach_(reach), firstView_(firstView) {
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
  if (reach < k)
    throw Error(ErrorCode::InvalidArgument, "--neighbour-reach " + std::to_string(reach) + ": must be at least " +
                                                "--neighbours (" + std::to_string(k) + ")");
  for (size_t i = 0; i < sequence_.size(); ++i) byInput_[sequence_[i].input] = i;
  slots_.resize(size_t(2 * k));
}

std::vector<size_t> NeighbourWindow::members(size_t index, size_t count, int k, int reach) {
  std::vector<size_t> out;
  // The unused frame nearest `at` (clamped into the shot), the earlier one of two as near.
  const auto add = [&](long at) {
    at = std::clamp(at, 0L, long(count) - 1);
    for (long d = 0; d < long(count); ++d)
      for (const long c : {at - d, at + d})
        if (c >= 0 && c < long(count) && size_t(c) != index &&
            std::find(out.begin(), out.end(), size_t(c)) == out.end()) {
          out.push_back(size_t(c));
          return;
        }
  };
  for (int j = 1; j <= k; ++j) {
    const long d = std::max(long(j), std::lround(double(reach) * j / k)), i = long(index);
    // A side the shot has no frame at goes to the other side, as far out.
    add(i - d >= 0 ? i - d : i + d);
    add(i + d < long(count) ? i + d : i - d);
  }
  std::sort(out.begin(), out.end());
  return out;
}

size_t NeighbourWindow::indexOf(const std::string& input) const {
  const auto it = byInput_.find(input);
  if (it == byInput_.end()) throw Error(ErrorCode::InvalidOperation, input + ": not a frame of the sequence");
  return it->second;
}

void NeighbourWindow::moveTo(Pipeline& pipeline, const std::string& input) {
  const size_t index = indexOf(input);
  const std::vector<size_t> window = members(index, sequence_.size(), k_, reach_);
  const auto wanted = [&](size_t j) { return std::find(window.begin(), window.end(), j) != window.end(); };
  // View k is the window's k-th frame, whichever frames went before: a shard's or a resumed run's
  // frame then has the views, in the order, of the whole run's (their order decides the `view`
  // channel and the rounding of sums over views). A frame that moves to another slot is set again.
  for (size_t k = 0; k < slots_.size(); ++k)
    if (slots_[k] != window[k]) slots_[k].reset();
  // Frames kept are this window's and the next frame's (frames go in order): the others are read
  // again when a later window wants them, so memory stays within 4K G-buffers however far the reach.
  const std::vector<size_t> next = windowAfter(index);
  for (auto it = loaded_.begin(); it != loaded_.end();)
    it = wanted(it->first) || std::find(next.begin(), next.end(), it->first) != next.end() ? std::next(it)
                                                                                           : loaded_.erase(it);
  for (size_t slot = 0; slot < window.size(); ++slot) {
    const size_t j = window[slot];
    if (slots_[slot]) continue;
    const FrameJob& job = sequence_[j];
    std::shared_ptr<const Frame>& frame = loaded_[j];
    if (!frame) try {
        FrameSource source = frameSource(input_, job);
        // A frame read again (a later window wants it back) was checked the first time.
        source.inputCheck = source.inputCheck && !checked_.count(j);
        frame = std::make_shared<const Frame>(loadFrame(source));
        checked_.insert(j);
      } catch (const Error& e) {
        loaded_.erase(j);
        throw Error(e.code(), "neighbour " + job.input + ": " + e.what());
      }
    slots_[slot] = j;
    pipeline.setView(firstView_ + int(slot), frame->gbuffer, frame->camera, job.input, ViewTime::Other);
  }
}

std::vector<size_t> NeighbourWindow::windowAfter(size_t index) const {
  return members(std::min(index + 1, sequence_.size() - 1), sequence_.size(), k_, reach_);
}

void NeighbourWindow::keep(const std::string& input, Frame&& frame) {
  const size_t index = indexOf(input);
  // A frame a slot still shows stays as it was read: the pipeline's view points into its images
  // (a frame traced with no moveTo, its window's blends all failed, could be shown from before).
  if (std::find(slots_.begin(), slots_.end(), index) != slots_.end()) return;
  const std::vector<size_t> wanted = windowAfter(index);
  if (std::find(wanted.begin(), wanted.end(), index) != wanted.end())
    loaded_[index] = std::make_shared<const Frame>(std::move(frame));
}

std::vector<std::string> NeighbourWindow::filesOf(const std::string& input) const {
  const size_t index = indexOf(input);
  std::vector<std::string> out;
  for (size_t j : members(index, sequence_.size(), k_, reach_)) out.push_back(sequence_[j].input);
  return out;
}

std::vector<std::string> NeighbourWindow::files() const {
  std::vector<std::string> out;
  for (const auto& slot : slots_)
    if (slot) out.push_back(sequence_[*slot].input);
  return out;
}

}  // namespace ssrcl::cli
