// Outputs stay bit-identical across refactorings: each run of tests/golden/runs.txt must give the
// digests recorded in tests/data/golden.txt (scripts/record-golden.sh, from the build that was
// the reference). The digests hold for the device they were recorded on; elsewhere the test skips.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "support/golden_runs.hpp"
#include "support/temp_dir.hpp"

namespace ssrcl::test {
namespace {

const std::string kSource = SSRCL_SOURCE_DIR;

struct Recorded {
  std::string device;
  std::map<std::string, std::string> lines;  // run name -> digest line
};

const Recorded& recorded() {
  static const Recorded r = [] {
    Recorded out;
    std::ifstream in(kSource + "/tests/data/golden.txt");
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("device: ", 0) == 0) out.device = line;
      else if (!line.empty() && line[0] != '#') out.lines[line.substr(0, line.find(' '))] = line;
    }
    return out;
  }();
  return r;
}

class Golden : public ::testing::TestWithParam<GoldenRun> {};

TEST_P(Golden, OutputBitsMatchTheRecording) {
  const GoldenRun& run = GetParam();
  ASSERT_FALSE(recorded().device.empty()) << "tests/data/golden.txt is missing or has no device line";
  if (goldenDeviceLine(SSRCL_CLI) != recorded().device)
    GTEST_SKIP() << "digests were recorded on " << recorded().device;
  auto it = recorded().lines.find(run.name);
  ASSERT_NE(it, recorded().lines.end()) << run.name << " not recorded: run scripts/record-golden.sh";
  const TempDir work("ssrcl-golden");
  EXPECT_EQ(goldenDigest(SSRCL_CLI, run, kSource, work.path().string()), it->second)
      << "ssrcl trace " << run.input << " " << run.options;
}

INSTANTIATE_TEST_SUITE_P(Runs, Golden, ::testing::ValuesIn(readGoldenRuns(kSource + "/tests/golden/runs.txt")),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace ssrcl::test
