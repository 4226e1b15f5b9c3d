#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "batch_plan.hpp"
#include "batch_runner.hpp"
#include "frame_sequence.hpp"

namespace ssrcl::cli {

// What a batch did, for its summary and its JSON report.
struct BatchOutcome {
  const std::vector<FrameJob>& jobs;
  const std::vector<FrameOutcome>& frames;
  BatchRun run;
  std::string device;
  Shard shard;
  int stopSignal = 0;  // the signal that interrupted it, 0 if none

  size_t count(FrameStatus status) const;
  double framesPerSecond() const;     // frames done per second of wall time
  double deviceBusyFraction() const;  // device time over wall time
};

// "12 frames: 9 done, 2 skipped, 1 failed ..." and a line per failed frame.
void printSummary(std::ostream& out, const BatchOutcome& batch);

// The JSON report: totals, rates, and each frame's paths, status, error and stage times.
// Written to a temporary file and renamed; Error(IoError) when it cannot be.
void writeReport(const std::string& path, const BatchOutcome& batch);

}  // namespace ssrcl::cli
