#pragma once
#include <functional>
#include <string>
#include <vector>

#include "batch_plan.hpp"
#include "gbuffer_input.hpp"
#include "neighbour_window.hpp"
#include "temporal_window.hpp"
#include "output_options.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

enum class FrameStatus {
  NotRun,   // not reached: interrupted, or stopped after a failure
  Done,     // output written
  Skipped,  // output existed (no --overwrite)
  Failed,
};
const char* statusName(FrameStatus status);

struct FrameOutcome {
  FrameStatus status = FrameStatus::NotRun;
  std::string error;                                             // why it failed: names the file and the problem
  int exitCode = 0;                                              // what the failure would make `ssrcl trace` exit with
  double readSeconds = 0, computeSeconds = 0, writeSeconds = 0;  // host wall time of each stage
  double deviceMs = 0;                                           // the pipeline's per-stage device times, summed
};

struct BatchRun {
  double wallSeconds = 0;
  double deviceMs = 0;  // over all frames: device busy fraction = deviceMs / 1000 / wallSeconds
  bool halted = false;  // stopped early by --fail-fast or a device that cannot run at all
};

// Runs frames through one Pipeline on one Device, so kernels are compiled once, while `ioThreads`
// threads read the next frames and as many write the previous ones.
class BatchRunner {
 public:
  // Frames are traced with `record.settings` and written as `output` asks, with `record`.
  BatchRunner(const Device& device, const GBufferInputOptions& input, const OutputRecord& record,
              const OutputOptions& output, bool failFast, int ioThreads);

  // Every frame's misses take this environment (see Pipeline::setEnvironment); it must outlive run().
  void setEnvironment(const EnvironmentMap& environment) { pipeline_.setEnvironment(environment); }
  // Auxiliary views of every frame (see Pipeline::setView), uploaded once; they must outlive run().
  void setViews(const Views& views) {
    cli::setViews(pipeline_, views);
    staticViews_ = views.files;
  }
  // Each frame's neighbours in the sequence as views too (after the static ones), read as needed.
  void setNeighbours(std::unique_ptr<NeighbourWindow> neighbours) { neighbours_ = std::move(neighbours); }
  // Each frame's pass blended with its neighbours' in the sequence (--temporal K).
  void setTemporal(std::unique_ptr<TemporalWindow> temporal) { temporal_ = std::move(temporal); }

  // Processes, in order, the jobs whose outcome is NotRun and records their outcomes. Starts no
  // new frame once stopRequested() is true; the frame on the device is finished and written.
  // frameFinished(i) is called once per frame done or failed, never two at a time.
  BatchRun run(const std::vector<FrameJob>& jobs, std::vector<FrameOutcome>& outcomes,
               const std::function<bool()>& stopRequested, const std::function<void(size_t)>& frameFinished);

 private:
  Pipeline pipeline_;
  std::vector<std::string> staticViews_;
  std::unique_ptr<NeighbourWindow> neighbours_;
  std::unique_ptr<TemporalWindow> temporal_;
  GBufferInputOptions input_;
  OutputRecord record_;
  OutputOptions output_;
  bool failFast_;
  int ioThreads_;
};

}  // namespace ssrcl::cli
