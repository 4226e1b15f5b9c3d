// Runtime OpenCL failures under `ssrcl trace` (issue 17): tests/fault_injection/opencl_fault.cpp,
// preloaded, fails the Nth call of one entry point. The CLI must exit 3 with a message naming the
// failed call, its status and where it happened, and leave an earlier output byte for byte intact.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/analytic_sequence.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace {

using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

struct Fault {
  const char* call;
  int at;              // which call of it fails
  const char* status;  // SSRCL_FAULT_STATUS, as the number and as the name the message must give
  const char* statusName;
  const char* where;  // the part of the pipeline the message must name
};

// The first kernel launch is the setup stage's, the first read its pixel counts, the first
// buffer and the first write belong to commit's allocation (the Hi-Z level table). The download
// maps the outputs on a device that works in host memory (PoCL's CPU device) and reads them back
// elsewhere (the second read): each device runs one of those two.
const Fault kFaults[] = {
    {"clEnqueueNDRangeKernel", 1, "-5", "CL_OUT_OF_RESOURCES", "(setup stage)"},
    {"clEnqueueReadBuffer", 1, "-5", "CL_OUT_OF_RESOURCES", "(setup stage)"},
    {"clEnqueueMapBuffer", 1, "-36", "CL_INVALID_COMMAND_QUEUE", "(download stage)"},
    {"clEnqueueReadBuffer", 2, "-36", "CL_INVALID_COMMAND_QUEUE", "(download stage)"},
    {"clCreateBuffer", 3, "-4", "CL_MEM_OBJECT_ALLOCATION_FAILURE", "allocating device buffers"},
    {"clEnqueueWriteBuffer", 1, "-5", "CL_OUT_OF_RESOURCES", "allocating device buffers"},
};

std::string faultName(const Fault& f) { return std::string(f.call) + "_" + std::to_string(f.at); }
void PrintTo(const Fault& f, std::ostream* os) { *os << faultName(f); }

class OpenClFault : public ::testing::TestWithParam<Fault> {
 protected:
  ssrcl::test::TempDir dir{"ssrcl-fault"};
  std::string frame, out = dir.file("out.exr");
  void SetUp() override {
    ssrcl::test::AnalyticSequence s;
    s.directory = dir.file("in");
    s.frameCount = 1;
    s.roughness = 0.3;  // glossy: every stage runs
    writeAnalyticSequence(s);
    frame = s.directory + "/shot.1001.exr";
  }
  // `ssrcl trace` under the injector; an ASan build's runtime tolerates a library preloaded before it.
  ssrcl::test::CommandResult trace(const std::string& call, int at, const std::string& status) {
    return runCommand("SSRCL_FAULT_CALL=" + call + " SSRCL_FAULT_AT=" + std::to_string(at) +
                      " SSRCL_FAULT_STATUS=" + status + " LD_PRELOAD=" + shellQuote(SSRCL_OPENCL_FAULT) +
                      " ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0\" " +
                      shellQuote(SSRCL_CLI) + " trace " + shellQuote(frame) + " -o " + shellQuote(out));
  }
};

TEST_P(OpenClFault, ExitsThreeNamingTheCallAndKeepsTheEarlierOutput) {
  const Fault& f = GetParam();
  // A good run first, through the injector with nothing failing: forwarding works, and this is
  // the earlier output the failed run must leave alone.
  auto good = trace(f.call, 1 << 30, f.status);
  ASSERT_EQ(good.exitCode, 0) << good.output;
  ASSERT_EQ(good.output.find("opencl_fault:"), std::string::npos) << good.output;
  const std::string before = ssrcl::test::readBytes(out);

  auto r = trace(f.call, f.at, f.status);
  const bool download = std::string(f.where) == "(download stage)";
  if (download && r.exitCode == 0 && r.output.find("opencl_fault:") == std::string::npos)
    GTEST_SKIP() << "this device downloads its outputs the other way (" << f.call << " not called)";
  // The injection happened (else this test would prove nothing).
  ASSERT_NE(r.output.find(std::string("opencl_fault: ") + f.call + " call " + std::to_string(f.at)), std::string::npos)
      << r.output;
  EXPECT_EQ(r.exitCode, 3) << r.output;
  for (const std::string needle : {std::string(f.call) + " failed with " + f.statusName + " (" + f.status + ")",
                                   std::string(f.where)})
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.output;
  EXPECT_EQ(ssrcl::test::readBytes(out), before);
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << e.path();
}

INSTANTIATE_TEST_SUITE_P(Injected, OpenClFault, ::testing::ValuesIn(kFaults),
                         [](const auto& info) { return faultName(info.param); });

}  // namespace
