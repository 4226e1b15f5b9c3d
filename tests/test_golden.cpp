// Outputs stay bit-identical across refactorings: each run of tests/golden/runs.txt must give the
// digests recorded for its device in tests/data/golden*.txt (scripts/record-golden.sh, from the build that was
// the reference). The digests hold for the device they were recorded on; elsewhere the test skips.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "support/golden_runs.hpp"
#include "support/temp_dir.hpp"

namespace ssrcl::test {
namespace {

const std::string kSource = SSRCL_SOURCE_DIR;

struct Recorded {
  std::string file, device;
  std::map<std::string, std::string> lines;  // run name -> digest line
};

Recorded readRecording(const std::filesystem::path& path) {
  Recorded out{path.filename().string(), "", {}};
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("device: ", 0) == 0) out.device = line;
    else if (!line.empty() && line[0] != '#') out.lines[line.substr(0, line.find(' '))] = line;
  }
  return out;
}

// Digests hold per device (each CPU kind PoCL compiles for rounds its own way): one recording per
// device, tests/data/golden*.txt, and the one of the device this test runs on.
const std::vector<Recorded>& recordings() {
  static const std::vector<Recorded> all = [] {
    std::vector<Recorded> out;
    for (const auto& entry : std::filesystem::directory_iterator(kSource + "/tests/data")) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("golden", 0) == 0 && entry.path().extension() == ".txt") out.push_back(readRecording(entry.path()));
    }
    return out;
  }();
  return all;
}

const Recorded* recordingOfThisDevice() {
  static const std::string device = goldenDeviceLine(SSRCL_CLI);
  for (const Recorded& r : recordings())
    if (r.device == device) return &r;
  return nullptr;
}

class Golden : public ::testing::TestWithParam<GoldenRun> {};

TEST_P(Golden, OutputBitsMatchTheRecording) {
  const GoldenRun& run = GetParam();
  ASSERT_FALSE(recordings().empty()) << "no tests/data/golden*.txt";
  const Recorded* recorded = recordingOfThisDevice();
  if (!recorded) GTEST_SKIP() << "no digests recorded on " << goldenDeviceLine(SSRCL_CLI);
  auto it = recorded->lines.find(run.name);
  ASSERT_NE(it, recorded->lines.end()) << run.name << " not recorded in " << recorded->file
                                       << ": run scripts/record-golden.sh";
  const TempDir work("ssrcl-golden");
  EXPECT_EQ(goldenDigest(SSRCL_CLI, run, kSource, work.path().string()), it->second)
      << "ssrcl trace " << run.input << " " << run.options;
}

INSTANTIATE_TEST_SUITE_P(Runs, Golden, ::testing::ValuesIn(readGoldenRuns(kSource + "/tests/golden/runs.txt")),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace ssrcl::test
