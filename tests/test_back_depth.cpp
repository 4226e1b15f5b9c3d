// The back-face depth pass (host/io/back_depth.cpp, kernels/thickness.cl known_thickness) as a
// user gives it: from a file of its own, or as the add-on's BackFaces layer of the frame's file;
// unknown values, a pass of another frame and one of another size; `ssrcl trace` end to end.
// The thickness it gives each pixel is checked against the CPU reference in test_differential.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ssrcl/ssrcl.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl;

const std::string kScene = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/thin_objects";

FrameSource sceneWithBack(const std::string& backFile) {
  FrameSource s;
  s.file = kScene + ".exr";
  s.backDepthFile = backFile;
  return s;
}

// The scene's front depth, as stored, for writing back passes made from it.
std::vector<float> frontDepth() { return test::readExr(kScene + ".exr").channels.at("ViewLayer.Depth.Z").values; }

void expectRefused(const FrameSource& s, const std::string& file, const std::string& part) {
  try {
    loadFrame(s);
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput) << message;
    EXPECT_EQ(message.rfind(file, 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// The corpus scene's rendered back pass (samples/blender/render_back_faces.py): known on the
// objects, never in front of the front, 0 (unknown) on the floor planes and the sky.
TEST(BackDepth, RenderedPassIsBehindTheFront) {
  const Frame f = loadFrame(sceneWithBack(kScene + ".back.exr"));
  const Image& back = f.gbuffer.backDepth;
  ASSERT_EQ(back.width, f.gbuffer.depth.width);
  size_t surface = 0, known = 0;
  for (size_t i = 0; i < back.data.size(); ++i) {
    const float d = f.gbuffer.depth.data[i], b = back.data[i];
    ASSERT_TRUE(std::isfinite(b));
    if (!(d > 0.0f && d < 1e10f)) {
      EXPECT_EQ(b, 0.0f);
      continue;
    }
    ++surface;
    if (b == 0.0f) continue;
    ++known;
    EXPECT_GT(b, d);
  }
  EXPECT_GT(known, surface / 10);
  EXPECT_LT(known, surface);  // the floor has no back
}

// NaN, negative, 1e10 and a back at the front are unknown; a few pixels in front (antialiased
// edges) are let through as unknown; the rest is kept as given.
TEST(BackDepth, UnknownValuesBecomeZero) {
  test::TempDir dir;
  std::vector<float> back = frontDepth();
  const int w = 480, h = 270;
  for (int i = 0; i < w * h; ++i) {
    const float d = back[i];
    if (!(d < 1e9f)) continue;
    switch (i % 7) {
      case 0: back[i] = NAN; break;
      case 1: back[i] = -1.0f; break;
      case 2: back[i] = 1e10f; break;
      case 3: back[i] = d; break;
      default: back[i] = (i % 251 == 0) ? 0.5f * d : 1.25f * d;  // in front on 0.4%
    }
  }
  test::writeExr(dir.file("back.exr"), w, h, {{"ViewLayer.Depth.Z", back}});
  const Frame f = loadFrame(sceneWithBack(dir.file("back.exr")));
  for (int i = 0; i < w * h; ++i) {
    const float d = f.gbuffer.depth.data[i], b = f.gbuffer.backDepth.data[i];
    if (!(d < 1e9f)) continue;
    if (i % 7 < 4 || i % 251 == 0) EXPECT_EQ(b, 0.0f) << "pixel " << i;
    else EXPECT_FLOAT_EQ(b, 1.25f * d) << "pixel " << i;
  }
}

TEST(BackDepth, PassInFrontOfTheFrontIsRefused) {
  test::TempDir dir;
  std::vector<float> back = frontDepth();
  for (size_t i = 0; i < back.size(); ++i)
    if (back[i] < 1e9f) back[i] *= (i % 20 == 0) ? 0.9f : 1.1f;  // 5% in front
  test::writeExr(dir.file("other.exr"), 480, 270, {{"ViewLayer.Depth.Z", back}});
  expectRefused(sceneWithBack(dir.file("other.exr")), dir.file("other.exr"), "in front of the depth on 5.0%");
}

TEST(BackDepth, WrongSizeOrChannelIsRefused) {
  test::TempDir dir;
  test::writeExr(dir.file("small.exr"), 48, 27, {{"ViewLayer.Depth.Z", std::vector<float>(48 * 27, 5.0f)}});
  expectRefused(sceneWithBack(dir.file("small.exr")), dir.file("small.exr"), "48x27");
  FrameSource s = sceneWithBack(kScene + ".back.exr");
  s.backDepthChannel = "Back.Z";
  expectRefused(s, kScene + ".back.exr", "'Back.Z'");
}

// The add-on's layout: the pass as BackFaces.Depth.Z of the frame's own file, read with no option.
TEST(BackDepth, BackFacesLayerOfTheFrameIsReadWithNoOption) {
  test::TempDir dir;
  test::ExrContents scene = test::readExr(kScene + ".exr");
  std::vector<test::ExrChannel> channels;
  for (const auto& [name, channel] : scene.channels) channels.push_back(channel);
  const std::vector<float> back = test::readExr(kScene + ".back.exr").channels.at("ViewLayer.Depth.Z").values;
  channels.push_back({"BackFaces.Depth.Z", back});
  test::writeExr(dir.file("frame.exr"), scene.width, scene.height, channels);
  std::filesystem::copy_file(kScene + ".camera.json", dir.file("frame.camera.json"));
  FrameSource own;
  own.file = dir.file("frame.exr");
  const Frame f = loadFrame(own), given = loadFrame(sceneWithBack(kScene + ".back.exr"));
  EXPECT_EQ(f.gbuffer.backDepth.data, given.gbuffer.backDepth.data);
  FrameSource plain;
  plain.file = kScene + ".exr";
  EXPECT_TRUE(loadFrame(plain).gbuffer.backDepth.empty());
}

// A pipeline reused for the next frame (as `ssrcl batch` reuses one) traces that frame with the
// passes it has: one without a back pass after one with it forgets the first's (which it read
// through a pointer left behind, the previous frame's images freed by then in a batch).
TEST(BackDepth, APipelineReusedForAFrameWithoutOneForgetsIt) {
  FrameSource plain;
  plain.file = kScene + ".exr";
  const Frame with = loadFrame(sceneWithBack(kScene + ".back.exr")), without = loadFrame(plain);
  const auto reflection = [](Pipeline& p, const Frame& f) {
    setFrame(p, f);
    p.commit();
    p.execute();
    return p.output("reflection").data;
  };
  Pipeline reused(test::sharedTestDevice()), fresh(test::sharedTestDevice());
  const std::vector<float> traced = reflection(reused, with), freshWithout = reflection(fresh, without);
  EXPECT_EQ(reflection(reused, without), freshWithout);
  const std::vector<float> freshWith = reflection(fresh, with);
  EXPECT_NE(freshWith, freshWithout);  // the pass matters on this scene
  EXPECT_EQ(freshWith, traced);
}

std::string inputsRecord(const std::string& exr) { return ssrcl::test::stringAttribute(exr, "ssrcl/inputs"); }

// `ssrcl trace --back-depth-file` (and --back-depth-channel): traced with it (recorded in
// ssrcl/inputs, a different pass),
// and a wrong one refused naming it, leaving no output.
TEST(BackDepth, TraceCommandReadsAndRecordsIt) {
  test::TempDir dir;
  const std::string cli = test::shellQuote(SSRCL_CLI) + " trace " + test::shellQuote(kScene + ".exr") +
                          " --quality draft -o ";
  const test::CommandResult with =
      test::runCommand(cli + test::shellQuote(dir.file("with.exr")) + " --back-depth-file " +
                       test::shellQuote(kScene + ".back.exr") + " --back-depth-channel ViewLayer.Depth.Z 2>&1");
  ASSERT_EQ(with.exitCode, 0) << with.output;
  const std::string record = inputsRecord(dir.file("with.exr"));
  EXPECT_NE(record.find("\"back_depth\":\"" + kScene + ".back.exr\""), std::string::npos) << record;
  EXPECT_NE(record.find("\"back_depth_channel\":\"ViewLayer.Depth.Z\""), std::string::npos) << record;
  const test::CommandResult without = test::runCommand(cli + test::shellQuote(dir.file("without.exr")) + " 2>&1");
  ASSERT_EQ(without.exitCode, 0) << without.output;
  EXPECT_EQ(inputsRecord(dir.file("without.exr")).find("back_depth"), std::string::npos);
  EXPECT_NE(test::readBytes(dir.file("with.exr")), test::readBytes(dir.file("without.exr")));

  const std::string wrong = kScene + ".exr";  // its own depth: the front, not the back faces
  const test::CommandResult refused = test::runCommand(cli + test::shellQuote(dir.file("bad.exr")) +
                                                       " --back-depth-file " + test::shellQuote(wrong) + " 2>&1");
  EXPECT_EQ(refused.exitCode, 2) << refused.output;
  EXPECT_NE(refused.output.find(wrong + ": the back-face depth equals the depth"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.exr")));
}

}  // namespace
