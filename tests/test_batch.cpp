// `ssrcl batch` as a user runs it on a generated shot: outputs identical to `ssrcl trace` and
// matching exact reflections, resumable, bad frames reported and skipped, a JSON report, shards,
// and Ctrl-C leaving nothing half-written.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "support/analytic_sequence.hpp"
#include "support/exr_fixtures.hpp"
#include "support/mirror_pass_match.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

constexpr int kFrames = 4;

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

json readJson(const std::string& path) { return json::parse(ssrcl::test::readBytes(path)); }

ino_t inode(const std::string& path) {
  struct stat s {};
  return stat(path.c_str(), &s) == 0 ? s.st_ino : 0;
}

// Hidden temporary files an interrupted write would leave.
std::vector<std::string> hiddenFiles(const fs::path& directory) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(directory, ec))
    if (e.path().filename().string()[0] == '.') found.push_back(e.path().string());
  return found;
}

class Batch : public ::testing::Test {
 protected:
  ssrcl::test::TempDir dir{"ssrcl-batch"};
  std::string frames;  // dir/in/shot.####.exr
  std::string outDir = dir.file("out");

  void SetUp() override {
    ssrcl::test::AnalyticSequence s;
    s.directory = dir.file("in");
    s.frameCount = kFrames;
    s.roughness = 0.3;  // glossy: seeded random rays, so "identical" covers the sampling too
    frames = ssrcl::test::writeAnalyticSequence(s);
  }
  std::string input(int frame) const { return dir.file("in/shot." + std::to_string(frame) + ".exr"); }
  std::string output(int frame) const { return outDir + "/shot." + std::to_string(frame) + ".refl.exr"; }
  ssrcl::test::CommandResult batch(const std::string& extra = "") {
    return runCommand(cli("batch " + shellQuote(frames) + " -o " + shellQuote(outDir + "/") + " " + extra));
  }
  void corrupt(int frame) { ssrcl::test::writeBytes(input(frame), "not an EXR file at all"); }
};

// `--temporal 0`: each frame alone, as `ssrcl trace` (the default blends its neighbours' passes:
// test_shot_temporal).
TEST_F(Batch, OutputsAreBitIdenticalToTrace) {
  auto r = batch("--temporal 0 --io-threads 3");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("4 done"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find('\r'), std::string::npos) << "no progress line when not a terminal: " << r.output;
  for (int f = 1001; f < 1001 + kFrames; ++f) {
    const std::string traced = dir.file("trace." + std::to_string(f) + ".exr");
    auto t = runCommand(cli("trace " + shellQuote(input(f)) + " -o " + shellQuote(traced)));
    ASSERT_EQ(t.exitCode, 0) << t.output;
    EXPECT_EQ(ssrcl::test::readBytes(output(f)), ssrcl::test::readBytes(traced)) << "frame " << f;
  }
  EXPECT_TRUE(hiddenFiles(outDir).empty());
}

// The test above compares batch with `ssrcl trace`, i.e. with itself. Against independent truth: a
// mirror shot's frames, each seen by its own camera (10 degrees apart), match their own exact
// reflections, and another frame's camera does not fit them. Without neighbours, whose views fill
// what lies off screen (test_multiview's Neighbours): the truth here holds those as misses.
TEST_F(Batch, MirrorFramesMatchTheirOwnExactReflections) {
  ssrcl::test::AnalyticSequence s;
  s.directory = dir.file("mirror");
  s.frameCount = 3;
  s.width = 160;
  s.height = 90;
  s.degreesPerFrame = 10.0;
  auto r = runCommand(cli("batch " + shellQuote(ssrcl::test::writeAnalyticSequence(s)) + " -o " +
                          shellQuote(outDir + "/") + " --edge-fade 0 --neighbours 0"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const ssrcl::test::Scene scene = ssrcl::test::sequenceScene(s);
  for (int i = 0; i < s.frameCount; ++i) {
    const auto m = ssrcl::test::matchExactReflections(output(1001 + i), scene, ssrcl::test::sequenceCamera(s, i));
    std::cout << "frame " << 1001 + i << ": visible hits matched " << m.visibleRate() << " of " << m.visible
              << ", misses " << m.missedRate() << " of " << m.missed << "\n";
    EXPECT_GE(m.visibleRate(), ssrcl::test::kMirrorPassFloor) << "frame " << 1001 + i;
    EXPECT_GE(m.missedRate(), ssrcl::test::kMirrorPassFloor) << "frame " << 1001 + i;
  }
  const auto wrongCamera = ssrcl::test::matchExactReflections(output(1003), scene, ssrcl::test::sequenceCamera(s, 0));
  std::cout << "frame 1003 against frame 1001's truth: " << wrongCamera.visibleRate() << "\n";
  EXPECT_LT(wrongCamera.visibleRate(), 0.8);
}

// A static view shared by every frame (--view, uploaded once) gives each frame what `ssrcl trace`
// gives it with the same view, bit for bit, and the view supplies hits the frames miss.
TEST_F(Batch, AStaticViewGivesWhatTraceGives) {
  ssrcl::test::AnalyticSequence wide;
  wide.directory = dir.file("views");
  wide.prefix = "wide";
  wide.frameCount = 1;
  wide.width = 128;
  wide.height = 72;
  wide.fovYDegrees = 90.0;
  wide.roughness = 0.3;
  ssrcl::test::writeAnalyticSequence(wide);
  const std::string view = dir.file("views/wide.1001.exr");
  auto r = batch("--temporal 0 --io-threads 2 --view " + shellQuote(view));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (int f = 1001; f < 1001 + kFrames; ++f) {
    const std::string traced = dir.file("trace." + std::to_string(f) + ".exr");
    auto t = runCommand(cli("trace " + shellQuote(input(f)) + " -o " + shellQuote(traced) + " --view " + shellQuote(view)));
    ASSERT_EQ(t.exitCode, 0) << t.output;
    EXPECT_EQ(ssrcl::test::readBytes(output(f)), ssrcl::test::readBytes(traced)) << "frame " << f;
    auto exr = ssrcl::test::readExr(output(f));
    ASSERT_TRUE(exr.channels.count("view")) << "frame " << f;
    const auto& source = exr.channels["view"].values;
    EXPECT_GT(std::count(source.begin(), source.end(), 1.0f), 0) << "frame " << f << ": the view supplied nothing";
  }
  r = batch("--overwrite --view " + shellQuote(dir.file("views/none.exr")));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("none.exr"), std::string::npos) << r.output;
}

TEST_F(Batch, SkipsExistingOutputsUnlessOverwrite) {
  ASSERT_EQ(batch().exitCode, 0);
  const ino_t first = inode(output(1001));
  auto again = batch("--report " + shellQuote(dir.file("r.json")));
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_EQ(readJson(dir.file("r.json"))["skipped"], kFrames);
  EXPECT_EQ(inode(output(1001)), first) << "a skipped output must not be rewritten";

  auto overwrite = batch("--overwrite --report " + shellQuote(dir.file("r.json")));
  ASSERT_EQ(overwrite.exitCode, 0) << overwrite.output;
  EXPECT_EQ(readJson(dir.file("r.json"))["done"], kFrames);
  EXPECT_NE(inode(output(1001)), first);
}

// A killed run (SIGKILL: no chance to clean up) leaves its temporary; a rerun removes it, also
// when the frame it belonged to was finished since and nothing is left to run. A hidden file
// that is not one of this batch's temporaries stays.
TEST_F(Batch, ResumeRemovesStaleTemporariesBesideFinishedFrames) {
  ASSERT_EQ(batch().exitCode, 0);
  const std::string stale = outDir + "/.shot.1002.refl.exr.tmp.99999", foreign = outDir + "/.keep.tmp.1";
  ssrcl::test::writeBytes(stale, "partial");
  ssrcl::test::writeBytes(foreign, "not ours");
  auto r = batch();
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(fs::exists(stale)) << r.output;
  EXPECT_TRUE(fs::exists(foreign));
}

// Each frame alone (`--temporal 0`): a bad frame fails itself only (blended, it fails the frames
// whose window holds it: ShotTemporal.AnUnreadableWindowFrameFailsOnlyTheFramesItBlendsInto).
TEST_F(Batch, ABadFrameIsReportedAndTheOthersAreDone) {
  corrupt(1002);
  auto r = batch("--temporal 0 --report " + shellQuote(dir.file("r.json")));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("frame 1002: " + input(1002)), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(output(1002)));
  for (int f : {1001, 1003, 1004}) EXPECT_TRUE(fs::exists(output(f))) << f;

  const json report = readJson(dir.file("r.json"));
  EXPECT_EQ(report["done"], 3);
  EXPECT_EQ(report["failed"], 1);
  const json& bad = report["frames"][1];
  EXPECT_EQ(bad["frame"], 1002);
  EXPECT_EQ(bad["status"], "failed");
  EXPECT_EQ(bad["exit_code"], 2);
  EXPECT_NE(bad["error"].get<std::string>().find(input(1002)), std::string::npos);
}

TEST_F(Batch, MissingFramesOfARangeFail) {
  auto r = batch("--temporal 0 --frames 1001-1005x2");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("frame 1005"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(output(1001)));
  EXPECT_TRUE(fs::exists(output(1003)));
  EXPECT_FALSE(fs::exists(output(1002)));
}

TEST_F(Batch, FailFastStopsAtTheFirstFailure) {
  corrupt(1002);
  auto r = batch("--temporal 0 --fail-fast --io-threads 1 --report " + shellQuote(dir.file("r.json")));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(fs::exists(output(1001)));
  EXPECT_FALSE(fs::exists(output(1003)));
  EXPECT_FALSE(fs::exists(output(1004)));
  const json report = readJson(dir.file("r.json"));
  EXPECT_EQ(report["not_run"], 2);
  EXPECT_EQ(report["stopped_at_failure"], true);
}

TEST_F(Batch, ReportHasTotalsRatesAndEachFrame) {
  ASSERT_EQ(batch("--report " + shellQuote(dir.file("sub/r.json"))).exitCode, 0);
  const json r = readJson(dir.file("sub/r.json"));
  EXPECT_EQ(r["frames_total"], kFrames);
  EXPECT_EQ(r["done"], kFrames);
  EXPECT_EQ(r["failed"], 0);
  EXPECT_EQ(r["interrupted"], false);
  EXPECT_GT(r["frames_per_second"].get<double>(), 0.0);
  EXPECT_GT(r["device_busy_fraction"].get<double>(), 0.0);
  EXPECT_FALSE(r["device"].get<std::string>().empty());
  ASSERT_EQ(r["frames"].size(), size_t(kFrames));
  const json& f = r["frames"][3];
  EXPECT_EQ(f["name"], "1004");
  EXPECT_EQ(f["input"], input(1004));
  EXPECT_EQ(f["output"], output(1004));
  EXPECT_EQ(f["status"], "done");
  EXPECT_GT(f["device_ms"].get<double>(), 0.0);
  for (const char* stage : {"read", "compute", "write"}) EXPECT_GE(f["seconds"][stage].get<double>(), 0.0);
}

TEST_F(Batch, GlobWithStemAndOneCamera) {
  const std::string camera = dir.file("in/shot.1001.camera.json");
  auto r = runCommand(cli("batch " + shellQuote(dir.file("in/*.exr")) + " -o " +
                          shellQuote(dir.file("g/{stem}_refl.exr")) + " --camera " + shellQuote(camera) +
                          " --temporal 0"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (int f = 1001; f < 1001 + kFrames; ++f)
    EXPECT_TRUE(fs::exists(dir.file("g/shot." + std::to_string(f) + "_refl.exr"))) << f;
  auto t = runCommand(cli("trace " + shellQuote(input(1003)) + " --camera " + shellQuote(camera) + " -o " +
                          shellQuote(dir.file("t.exr"))));
  ASSERT_EQ(t.exitCode, 0) << t.output;
  EXPECT_EQ(ssrcl::test::readBytes(dir.file("g/shot.1003_refl.exr")), ssrcl::test::readBytes(dir.file("t.exr")));
}

TEST_F(Batch, ShardsShareTheFramesDisjointly) {
  std::multiset<std::string> done;
  for (int k = 0; k < 3; ++k) {
    const std::string report = dir.file("r" + std::to_string(k) + ".json");
    auto r = batch("--shard " + std::to_string(k) + "/3 --report " + shellQuote(report));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const json frames = readJson(report)["frames"];
    for (const json& f : frames) {
      EXPECT_EQ(f["status"], "done");
      done.insert(f["name"].get<std::string>());
    }
  }
  EXPECT_EQ(done, (std::multiset<std::string>{"1001", "1002", "1003", "1004"}));
  EXPECT_EQ(batch("--shard 3/3").exitCode, 2);
}

TEST_F(Batch, UsageErrors) {
  EXPECT_EQ(batch("--frames 5-1").exitCode, 2);
  EXPECT_EQ(runCommand(cli("batch " + shellQuote(frames) + " -o " + shellQuote(dir.file("one.exr")))).exitCode, 2);
  EXPECT_EQ(runCommand(cli("batch " + shellQuote(dir.file("in/x.####.exr")) + " -o o/")).exitCode, 2);
  EXPECT_EQ(batch("--device 99").exitCode, 3);
}

// Starts the CLI in the background, its output to `log`; returns its pid.
pid_t start(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  std::vector<std::string> all = {SSRCL_CLI};
  all.insert(all.end(), args.begin(), args.end());
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  pid_t pid = -1;
  posix_spawn(&pid, SSRCL_CLI, &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  return pid;
}

TEST_F(Batch, InterruptLeavesNoPartialFileAndARerunFinishes) {
  // Slower frames (reference rays), so the signal lands with frames still to do: the first is
  // written once the 6 frames of its window (--temporal 5) are traced.
  const int total = 9;
  ssrcl::test::AnalyticSequence s;
  s.directory = dir.file("slow");
  s.frameCount = total;
  s.width = 160;
  s.height = 90;
  s.roughness = 0.3;
  const std::string slow = ssrcl::test::writeAnalyticSequence(s);
  const std::vector<std::string> args = {"batch", slow, "-o", outDir + "/", "--quality", "reference", "--spp", "64"};

  const pid_t pid = start(args, dir.file("log"));
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(output(1001)) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(fs::exists(output(1001)));
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string log = ssrcl::test::readBytes(dir.file("log"));
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT) << log;
  EXPECT_NE(log.find("interrupted"), std::string::npos) << log;

  EXPECT_TRUE(hiddenFiles(outDir).empty());
  std::set<int> written;
  for (int f = 1001; f < 1001 + total; ++f)
    if (fs::exists(output(f))) {
      written.insert(f);
      EXPECT_EQ(ssrcl::test::readExr(output(f)).width, 160) << "incomplete output " << f;
    }
  ASSERT_LT(written.size(), size_t(total)) << "the signal came too late to test anything: " << log;

  std::vector<std::string> rerun = args;
  rerun.insert(rerun.end(), {"--report", dir.file("r.json")});
  std::string command = shellQuote(SSRCL_CLI);
  for (const std::string& a : rerun) command += " " + shellQuote(a);
  auto r = runCommand(command);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json report = readJson(dir.file("r.json"));
  EXPECT_EQ(report["skipped"], written.size());
  EXPECT_EQ(report["done"], total - written.size());
  for (int f = 1001; f < 1001 + total; ++f) EXPECT_TRUE(fs::exists(output(f))) << f;
}

}  // namespace
