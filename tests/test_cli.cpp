// The `ssrcl` command as a user runs it: exit codes, one-line errors naming the file and channel,
// outputs that are complete or absent, never a clobbered file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <filesystem>

#include "ssrcl/ssrcl.hpp"
#include "support/analytic_sequence.hpp"
#include "support/exr_fixtures.hpp"
#include "support/mirror_pass_match.hpp"
#include "support/run_command.hpp"
#include "support/simple_camera.hpp"
#include "support/temp_dir.hpp"

namespace {

using ssrcl::test::ExrChannel;
using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

constexpr int kW = 40, kH = 30;

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

// A small Blender-style G-buffer: a floor plane seen by the test camera, with a colour ramp.
void writeShot(const std::string& exr, const std::vector<std::string>& skip = {}) {
  ssrcl::Camera cam = ssrcl::test::perspectiveCamera(kW, kH);
  std::vector<float> r(kW * kH), g(kW * kH), b(kW * kH, 0.25f), z(kW * kH), nx(kW * kH, 0.0f), ny(kW * kH, 1.0f),
      nz(kW * kH, 0.0f), rough(kW * kH, 0.0f);
  glm::dmat4 inv = glm::inverse(cam.projection * cam.view);
  glm::dvec3 eye = glm::dvec3(glm::inverse(cam.view)[3]);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int i = y * kW + x;
      glm::dvec4 p = inv * glm::dvec4(2.0 * (x + 0.5) / kW - 1.0, 1.0 - 2.0 * (y + 0.5) / kH, 1.0, 1.0);
      glm::dvec3 dir = glm::normalize(glm::dvec3(p) / p.w - eye);
      double t = dir.y < 0 ? -eye.y / dir.y : -1.0;  // floor y = 0
      z[i] = t > 0 ? float(-(cam.view * glm::dvec4(eye + t * dir, 1.0)).z) : 1e10f;
      r[i] = float(x) / kW;
      g[i] = float(y) / kH;
    }
  std::vector<ExrChannel> channels = {
      {"ViewLayer.Combined.R", r, Imf::HALF}, {"ViewLayer.Combined.G", g, Imf::HALF},
      {"ViewLayer.Combined.B", b, Imf::HALF}, {"ViewLayer.Depth.Z", z, Imf::FLOAT},
      {"ViewLayer.Normal.X", nx, Imf::FLOAT}, {"ViewLayer.Normal.Y", ny, Imf::FLOAT},
      {"ViewLayer.Normal.Z", nz, Imf::FLOAT}, {"ViewLayer.roughness.X", rough, Imf::FLOAT}};
  std::vector<ExrChannel> kept;
  for (auto& c : channels)
    if (std::find(skip.begin(), skip.end(), c.name) == skip.end()) kept.push_back(c);
  ssrcl::test::writeExr(exr, kW, kH, kept);
}

void writeCamera(const std::string& path, int w = kW, int h = kH) {
  ssrcl::saveCameraJson(path, ssrcl::test::perspectiveCamera(w, h));
}

class Cli : public ::testing::Test {
 protected:
  ssrcl::test::TempDir dir{"ssrcl-cli"};
  std::string shot = dir.file("shot.exr");
  std::string out = dir.file("shot.refl.exr");
  void SetUp() override {
    writeShot(shot);
    writeCamera(dir.file("shot.camera.json"));
  }
  // The command failed with `code`, said `needle` on one line, and wrote nothing.
  void expectFailure(const std::string& args, int code, const std::string& needle) {
    auto r = runCommand(cli(args));
    EXPECT_EQ(r.exitCode, code) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
    for (auto& e : std::filesystem::directory_iterator(dir.path()))
      EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "left behind: " << e.path();
  }
};

TEST_F(Cli, TraceWritesACompleteReflectionPass) {
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto exr = ssrcl::test::readExr(out);
  ASSERT_EQ(exr.width, kW);
  ASSERT_EQ(exr.height, kH);
  for (const char* c : {"R", "G", "B", "A", "distance"}) ASSERT_TRUE(exr.channels.count(c)) << c;
  int hits = 0;
  for (int i = 0; i < kW * kH; ++i) {
    float a = exr.channels["A"].values[i];
    EXPECT_TRUE(a >= 0.0f && a <= 1.0f);
    for (const char* c : {"R", "G", "B", "distance"}) EXPECT_TRUE(std::isfinite(exr.channels[c].values[i]));
    hits += a > 0;
  }
  // The floor reflects the sky only (nothing stands on it): every ray must miss.
  EXPECT_EQ(hits, 0);
}

// The pass `ssrcl trace` writes for an analytic mirror scene against its exact reflections (the
// test above can only see misses): colour on visible hits, A = 0 on misses.
TEST_F(Cli, TraceMatchesExactReflectionsOfAnAnalyticShot) {
  ssrcl::test::AnalyticSequence shotSpec;
  shotSpec.directory = dir.file("analytic");
  shotSpec.frameCount = 1;
  shotSpec.width = 160;
  shotSpec.height = 90;
  ssrcl::test::writeAnalyticSequence(shotSpec);
  const std::string frame = shotSpec.directory + "/shot.1001.exr";
  auto r = runCommand(cli("trace " + shellQuote(frame) + " --edge-fade 0 -o " + shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  using namespace ssrcl::test;
  const MirrorPassMatch m = matchExactReflections(out, sequenceScene(shotSpec), sequenceCamera(shotSpec, 0));
  std::cout << "analytic shot: " << m.visibleOk << " of " << m.visible << " visible hits match, " << m.missedOk
            << " of " << m.missed << " misses have A = 0\n";
  ASSERT_GT(m.visible, std::size_t(shotSpec.width * shotSpec.height / 20));
  EXPECT_GE(m.visibleRate(), kMirrorPassFloor);
  EXPECT_GE(m.missedRate(), kMirrorPassFloor);
}

TEST_F(Cli, ExplicitCameraAndDevice) {
  std::string cam = dir.file("other.json");
  writeCamera(cam);
  auto r = runCommand(cli("trace " + shellQuote(shot) + " --camera " + shellQuote(cam) + " --device cpu --stats -o " +
                          shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("trace"), std::string::npos) << r.output;  // per-stage times printed
  EXPECT_EQ(r.output.find("views"), std::string::npos) << r.output;  // no views, no views stage
  EXPECT_TRUE(std::filesystem::exists(out));
}

TEST_F(Cli, DevicesListsTheDefault) {
  auto r = runCommand(cli("devices"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("* 0"), std::string::npos) << r.output;
}

TEST_F(Cli, MissingChannelNamesFileAndChannel) {
  writeShot(shot, {"ViewLayer.Depth.Z"});
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, "ViewLayer.Depth.Z");
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(out)));
  EXPECT_NE(r.output.find(shot), std::string::npos) << r.output;
}

TEST_F(Cli, MissingRoughnessCanBeReplacedByAConstant) {
  writeShot(shot, {"ViewLayer.roughness.X"});
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, "ViewLayer.roughness.X");
  auto r = runCommand(cli("trace " + shellQuote(shot) + " --roughness 0 -o " + shellQuote(out)));
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST_F(Cli, CameraSizeMismatch) {
  writeCamera(dir.file("shot.camera.json"), kW + 1, kH);
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, "shot.camera.json");
}

TEST_F(Cli, MissingCameraSidecar) {
  std::filesystem::remove(dir.file("shot.camera.json"));
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, "shot.camera.json");
}

TEST_F(Cli, SingularCamera) {
  ssrcl::test::writeBytes(dir.file("shot.camera.json"), R"({"view": [[0,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
    "projection": [[1,0,0,0],[0,1,0,0],[0,0,-1.002,-0.2002],[0,0,-1,0]], "width": 40, "height": 30})");
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, "view");
}

TEST_F(Cli, NotAnExrFile) {
  ssrcl::test::writeBytes(shot, "\x89PNG\r\n\x1a\n not really a png either");
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out), 2, shot);
}

// Auxiliary views (--view) are read like the input, each camera from its sidecar or the
// --view-camera in its place; a bad one is named. The pass says where its hits came from.
TEST_F(Cli, ViewsAreReadLikeTheInputAndNamedWhenBad) {
  const std::string view = dir.file("side.exr"), sidecar = dir.file("side.camera.json");
  const std::string traced = "trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --view " + shellQuote(view);
  writeShot(view);
  writeCamera(sidecar);
  auto r = runCommand(cli(traced));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto exr = ssrcl::test::readExr(out);
  ASSERT_TRUE(exr.channels.count("view") && exr.channels.count("view_share"));
  // The floor reflects the sky in the frame and in the view: no source found anything.
  for (int i = 0; i < kW * kH; ++i) {
    EXPECT_EQ(exr.channels["view"].values[i], -1.0f);
    EXPECT_EQ(exr.channels["view_share"].values[i], 0.0f);
  }
  std::filesystem::remove(out);

  writeShot(view, {"ViewLayer.Normal.X"});
  expectFailure(traced, 2, "view " + view);
  writeShot(view);
  std::filesystem::rename(sidecar, dir.file("elsewhere.json"));
  expectFailure(traced, 2, "side.camera.json");
  expectFailure(traced + " --view-camera " + shellQuote(dir.file("nothing.json")), 2, "nothing.json");
  r = runCommand(cli(traced + " --view-camera " + shellQuote(dir.file("elsewhere.json"))));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::filesystem::remove(out);
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --view-camera " + shellQuote(sidecar), 2,
                "--view-camera");
}

TEST_F(Cli, BadOptionsAreUsageErrors) {
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --max-roughness 7", 2, "max-roughness");
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --no-such-option", 2, "no-such-option");
  expectFailure("trace " + shellQuote(shot), 2, "output");
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --device 99", 3, "99");
  expectFailure("trace " + shellQuote(shot) + " -o " + shellQuote(out) + " --device fast", 2, "--device");
}

TEST_F(Cli, NeverOverwritesTheInput) {
  std::string before = ssrcl::test::readBytes(shot);
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(shot)));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(ssrcl::test::readBytes(shot), before);
}

TEST_F(Cli, FailedRunLeavesAnExistingOutputUntouched) {
  ssrcl::test::writeBytes(out, "an earlier, good result");
  writeShot(shot, {"ViewLayer.Normal.Y"});
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(out)));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_EQ(ssrcl::test::readBytes(out), "an earlier, good result");
}

TEST_F(Cli, UnwritableOutputExitsWithOutputError) {
  std::string target = dir.file("no-such-dir/out.exr");
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(target)));
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("no-such-dir"), std::string::npos) << r.output;
}

TEST_F(Cli, PerPassFilesAndPlainChannelNames) {
  std::vector<float> rgb(kW * kH, 0.5f), nrm(kW * kH, 0.0f), up(kW * kH, 1.0f);
  auto gb = ssrcl::loadGBuffer([&] {
    ssrcl::GBufferSource s;
    s.file = shot;
    return s;
  }());
  ssrcl::test::writeExr(dir.file("c.exr"), kW, kH, {{"R", rgb}, {"G", rgb}, {"B", rgb}});
  ssrcl::test::writeExr(dir.file("z.exr"), kW, kH, {{"Z", gb.depth.data}});
  ssrcl::test::writeExr(dir.file("n.exr"), kW, kH, {{"N.X", nrm}, {"N.Y", up}, {"N.Z", nrm}});
  auto r =
      runCommand(cli("trace --layer '' --color " + shellQuote(dir.file("c.exr")) + " --depth " +
                     shellQuote(dir.file("z.exr")) + " --normal " + shellQuote(dir.file("n.exr")) +
                     " --roughness 0 --camera " + shellQuote(dir.file("shot.camera.json")) + " -o " + shellQuote(out)));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace
