#pragma once
// Golden outputs: digests of the raw float bits of `ssrcl trace` outputs for a fixed set of runs
// (tests/golden/runs.txt), so a refactoring can be checked to change no output bit.
#include <ostream>
#include <string>
#include <vector>

namespace ssrcl::test {

struct GoldenRun {
  std::string name, input, options;
};
// For test names and messages: "name: input options".
void PrintTo(const GoldenRun& run, std::ostream* os);

// The runs listed in `runsFile` (name | input | options, '#' comments).
std::vector<GoldenRun> readGoldenRuns(const std::string& runsFile);

// Runs `cli trace` on one run (input relative to `sourceDir`, output under `workDir`) and returns
// "name R:<hash> G:<hash> B:<hash> A:<hash> distance:<hash>" (FNV-1a 64 of each channel's bits).
// Throws std::runtime_error with the command's output when it fails.
std::string goldenDigest(const std::string& cli, const GoldenRun& run, const std::string& sourceDir,
                         const std::string& workDir);

// "device: <name>" as `cli devices` names the device the runs use (the digests hold for it only).
std::string goldenDeviceLine(const std::string& cli);

}  // namespace ssrcl::test
