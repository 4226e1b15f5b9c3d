#pragma once

namespace ssrcl::cli {

// Ctrl-C (SIGINT) and SIGTERM (what Slurm's scancel sends) ask a long run to stop after the frame
// in hand instead of killing it mid-write; a second signal ends the process at once.
class StopSignal {
 public:
  StopSignal();   // installs the handlers
  ~StopSignal();  // restores the previous ones
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;

  bool requested() const;
  int signal() const;  // the signal received, 0 if none
};

}  // namespace ssrcl::cli
