#include "batch_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "bounded_queue.hpp"
#include "exit_codes.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::cli {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

constexpr size_t kNotOwned = size_t(-1);

// A frame on its way through the stages; `outcome` gathers each stage's time, or the failure.
struct FrameInFlight {
  size_t index = 0;     // in the jobs; kNotOwned: a frame of --temporal windows only, not written
  size_t sequence = 0;  // in the whole sequence (--temporal)
  FrameOutcome outcome;
  std::optional<Error> error;  // why it failed, as thrown (a --temporal window's frame names it)
  Frame frame;
  Image reflection, distance, view;  // view: with auxiliary views only
  // Its output's header: made once it is traced, while its G-buffer (which says whether a back-face
  // pass was read) is still held.
  ReflectionExrOptions written;
  bool deviceUnusable = false;  // no later frame can succeed either: stop rather than fail each
};

// Runs one stage of a frame, timing it into `seconds`; a failure is recorded in the outcome.
template <class Stage>
bool attempt(FrameInFlight& f, double& seconds, int ioExitCode, Stage&& stage) {
  const Clock::time_point start = Clock::now();
  try {
    stage();
    seconds = secondsSince(start);
    return true;
  } catch (const Error& e) {
    f.error = e;
    f.outcome.error = e.what();
    f.outcome.exitCode = e.code() == ErrorCode::IoError ? ioExitCode : exitCodeFor(e.code());
    f.deviceUnusable = e.code() == ErrorCode::KernelBuild || e.code() == ErrorCode::NoDevice;
  } catch (const std::exception& e) {
    f.outcome.error = std::string("internal error: ") + e.what();
    f.error = Error(ErrorCode::InvalidOperation, f.outcome.error);
    f.outcome.exitCode = kExitInternal;
  }
  f.outcome.status = FrameStatus::Failed;
  return false;
}

}  // namespace

const char* statusName(FrameStatus status) {
  switch (status) {
    case FrameStatus::NotRun:
      return "not_run";
    case FrameStatus::Done:
      return "done";
    case FrameStatus::Skipped:
      return "skipped";
    case FrameStatus::Failed:
      return "failed";
  }
  return "?";
}

BatchRunner::BatchRunner(const Device& device, const GBufferInputOptions& input, const OutputRecord& record,
                         const OutputOptions& output, bool failFast, int ioThreads)
    : pipeline_(device),
      input_(input),
      record_(record),
      output_(output),
      failFast_(failFast),
      ioThreads_(std::max(1, ioThreads)) {
  pipeline_.settings() = record.settings;
}

BatchRun BatchRunner::run(const std::vector<FrameJob>& jobs, std::vector<FrameOutcome>& outcomes,
                          const std::function<bool()>& stopRequested,
                          const std::function<void(size_t)>& frameFinished) {
  const Clock::time_point start = Clock::now();
  BatchRun result;
  std::atomic<bool> halted{false};
  std::mutex finishing;
  const auto stopping = [&] { return halted.load() || stopRequested(); };
  const auto finish = [&](FrameInFlight& f) {
    std::lock_guard<std::mutex> lock(finishing);
    if (f.outcome.status != FrameStatus::Failed) f.outcome.status = FrameStatus::Done;
    result.deviceMs += f.outcome.deviceMs;
    if (f.outcome.status == FrameStatus::Failed && (failFast_ || f.deviceUnusable)) halted = true;
    outcomes[f.index] = f.outcome;
    frameFinished(f.index);
  };

  // Each I/O thread holds a frame, and each queue as many again: enough to hide reading and
  // writing behind the device, with a bounded number of frames in memory.
  BoundedQueue<FrameInFlight> read(ioThreads_), computed(ioThreads_);
  // What is read, in order: the frames to run, or with --temporal every frame of their windows
  // (each read and traced once, kept while a window holds it).
  std::vector<std::pair<size_t, size_t>> toRead;  // (job or kNotOwned, sequence index)
  std::vector<std::string> inputs;
  std::map<std::string, size_t> jobOf;
  for (size_t i = 0; i < jobs.size(); ++i)
    if (outcomes[i].status == FrameStatus::NotRun) {
      toRead.push_back({i, 0});
      inputs.push_back(jobs[i].input);
      jobOf[jobs[i].input] = i;
    }
  if (temporal_) {
    toRead.clear();
    for (size_t s : temporal_->plan(inputs)) {
      const auto own = jobOf.find(temporal_->job(s).input);
      toRead.push_back({own == jobOf.end() ? kNotOwned : own->second, s});
    }
  }
  std::atomic<size_t> nextToRead{0};
  std::atomic<int> readersLeft{ioThreads_};
  std::vector<std::thread> io;
  for (int t = 0; t < ioThreads_; ++t) {
    io.emplace_back([&] {
      for (size_t k; !stopping() && (k = nextToRead++) < toRead.size();) {
        FrameInFlight f;
        f.index = toRead[k].first;
        f.sequence = toRead[k].second;
        attempt(f, f.outcome.readSeconds, kExitUsage, [&] {
          const FrameJob& job = f.index == kNotOwned ? temporal_->job(f.sequence) : jobs[f.index];
          f.frame = loadFrame(frameSource(input_, job));
        });
        if (!read.push(std::move(f))) break;
      }
      if (--readersLeft == 0) read.close();
    });
    io.emplace_back([&] {
      while (std::optional<FrameInFlight> f = computed.pop()) {
        attempt(*f, f->outcome.writeSeconds, kExitOutput, [&] {
          const std::filesystem::path parent = std::filesystem::path(jobs[f->index].output).parent_path();
          if (!parent.empty()) std::filesystem::create_directories(parent);
          ReflectionExrOptions written = f->written;
          if (!f->view.empty()) written.view = &f->view;
          writeReflectionExr(jobs[f->index].output, f->reflection, f->distance, written);
        });
        finish(*f);
      }
    });
  }

  // A traced frame's pass in the output form, its record, and its G-buffer released (kept as
  // its successors' neighbour view, where they have some).
  const auto complete = [&](FrameInFlight& f) {
    const std::string& input = jobs[f.index].input;
    // Here, while the frame's material passes are still held: the G-buffer is released below.
    toOutputForm(input_.form, f.reflection, f.frame.gbuffer, f.frame.camera, input_.roughness);
    OutputRecord record = record_;
    record.views = staticViews_;
    if (temporal_) record.temporal = temporal_->filesOf(input);
    if (neighbours_) {
      // The views this frame was traced with: with --temporal, later traces have moved them since.
      const std::vector<std::string> neighbours = temporal_ ? neighbours_->filesOf(input) : neighbours_->files();
      record.views.insert(record.views.end(), neighbours.begin(), neighbours.end());
    }
    f.written = writerOptions(output_, record, input, f.frame.passes, f.frame);
    if (neighbours_ && !temporal_) {
      Frame traced;  // its next frames' neighbour
      traced.gbuffer = std::move(f.frame.gbuffer);
      traced.camera = f.frame.camera;
      neighbours_->keep(input, std::move(traced));
    }
    f.frame.gbuffer = GBuffer{};
  };
  std::deque<FrameInFlight> waiting;  // --temporal: traced, waiting for the rest of their window
  double windowMs = 0;                // device time of window frames not written, until the next blend
  while (std::optional<FrameInFlight> f = read.pop()) {
    if (stopping()) break;  // frames read ahead are abandoned: nothing of them was written
    if (!temporal_) {
      if (f->outcome.status == FrameStatus::Failed) {
        finish(*f);
        continue;
      }
      const bool computedOk = attempt(*f, f->outcome.computeSeconds, kExitUsage, [&] {
        if (neighbours_) neighbours_->moveTo(pipeline_, jobs[f->index].input);
        setFrame(pipeline_, f->frame);
        pipeline_.commit();
        pipeline_.execute();
        for (const auto& [stage, ms] : pipeline_.stageTimes().ms) f->outcome.deviceMs += ms;
        f->reflection = pipeline_.output("reflection");  // copies: the pipeline reuses its outputs
        f->distance = pipeline_.output("distance");
        f->view = pipeline_.output("view");  // empty without views
        complete(*f);
      });
      if (!computedOk)
        finish(*f);
      else
        computed.push(std::move(*f));
      continue;
    }
    const bool own = f->index != kNotOwned;
    if (f->outcome.status != FrameStatus::Failed)
      attempt(*f, f->outcome.computeSeconds, kExitUsage, [&] {
        const double ms = temporal_->trace(pipeline_, neighbours_.get(), f->sequence, f->frame);
        (own ? f->outcome.deviceMs : windowMs) += ms;
        if (neighbours_) {
          Frame traced;  // its next frames' neighbour; a frame to write keeps its own until blended
          traced.gbuffer = own ? f->frame.gbuffer : std::move(f->frame.gbuffer);
          traced.camera = f->frame.camera;
          neighbours_->keep(temporal_->job(f->sequence).input, std::move(traced));
        }
      });
    if (f->outcome.status == FrameStatus::Failed) {
      temporal_->fail(f->sequence, *f->error);
      if (own) {
        temporal_->release(jobs[f->index].input);
        finish(*f);
      }
    } else if (own) {
      waiting.push_back(std::move(*f));
    }
    for (auto it = waiting.begin(); it != waiting.end();) {
      if (!temporal_->ready(jobs[it->index].input)) {
        ++it;
        continue;
      }
      FrameInFlight g = std::move(*it);
      it = waiting.erase(it);
      g.outcome.deviceMs += windowMs;
      windowMs = 0;
      double seconds = 0;
      const bool blended = attempt(g, seconds, kExitUsage, [&] {
        TemporalWindow::Pass pass = temporal_->blend(pipeline_, jobs[g.index].input);
        g.reflection = std::move(pass.reflection);
        g.distance = std::move(pass.distance);
        g.view = std::move(pass.view);
        complete(g);
      });
      g.outcome.computeSeconds += seconds;
      if (!blended)
        finish(g);
      else
        computed.push(std::move(g));
    }
  }
  read.close();
  computed.close();
  for (std::thread& t : io) t.join();
  result.halted = halted;
  result.wallSeconds = secondsSince(start);
  return result;
}

}  // namespace ssrcl::cli
