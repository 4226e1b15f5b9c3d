// Auxiliary views (Pipeline::setView) on analytic mirror scenes against exact ray-traced truth:
// reflections the main frame cannot show (off screen, or hidden behind another surface) are found
// in another G-buffer of the same scene that sees them, and only there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <utility>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"
#include "support/analytic_sequence.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/scoped_env.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::test;
using glm::dvec3;

// As tests/test_mirror_analytic.cpp: the colour pattern's gradient allows 0.05 per pixel of hit
// error, plus what the truth measures one pixel around the hit.
constexpr double kColorTol = 0.05;

struct View {
  ssrcl::Camera camera;
  AnalyticGBuffer g;
};

View renderView(const Scene& scene, const ViewParams& params, int width, int height) {
  View v;
  v.camera = makeCamera(params, width, height);
  v.g = renderGBuffer(scene, v.camera);
  return v;
}

// The exact hit is what the view shows where it projects, clear of the view's faded border.
bool seenBy(const View& v, const MirrorSample& s) {
  const dvec3 p = projectToScreen(v.camera, s.hit.position);
  const double margin = 0.05 * std::min(v.camera.width, v.camera.height) + 2.0;
  if (!(p.z > v.camera.nearPlane) || p.x < margin || p.y < margin || p.x > v.camera.width - margin ||
      p.y > v.camera.height - margin)
    return false;
  const Hit& h = v.g.hit(int(p.x), int(p.y));
  return h.primitive == s.hit.primitive && glm::length(h.position - s.hit.position) < 0.02 * p.z;
}

double maxAbsDiff(const dvec3& expected, const ssrcl::Image& img, int x, int y) {
  double d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(double(img.at(x, y, c)) - expected[c]));
  return d;
}

// The scene seen through a 30-degree lens (the frame) and a 75-degree one (the view) from the same
// eye: the view shows what the frame's floor reflects from above it.
std::pair<ViewParams, ViewParams> narrowAndWide(const Scene& scene) {
  ViewParams frame = scene.view, wide = scene.view;
  frame.fovYDegrees = 30.0;
  wide.fovYDegrees = 75.0;
  return {frame, wide};
}

struct Pass {
  ssrcl::Image reflection, view;
};

Pass trace(const AnalyticGBuffer& g, const ssrcl::Camera& camera, const std::vector<const View*>& views,
           ssrcl::ViewTime time = ssrcl::ViewTime::Same,
           float viewRadianceCap = ssrcl::TraceSettings{}.viewRadianceCap) {
  ssrcl::Device device = testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(g);
  p.setCamera(camera);
  for (size_t k = 0; k < views.size(); ++k) p.setView(int(k), views[k]->g, views[k]->camera, {}, time);
  p.settings().edgeFade = 0;  // the truth has no fade
  p.settings().viewRadianceCap = viewRadianceCap;
  p.commit();
  p.execute();
  return {p.output("reflection"), p.output("view")};
}

struct Score {
  size_t pixels = 0, exact = 0, found = 0, fromView = 0;
  double fraction(size_t n) const { return pixels ? double(n) / pixels : 0.0; }
};

// Over the main frame's pixels of class `cls` whose exact hit `view` sees (off-screen hits more
// than 2 pixels outside the frame, which one pixel of hit error cannot bring back): how many carry the exact
// colour at full confidence, how many found anything, how many name the view as their source.
Score score(const AnalyticGBuffer& g, const MirrorTruth& truth, ReflectionClass cls, const View& view, const Pass& pass) {
  Score s;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const MirrorSample& m = truth.at(x, y);
      if (m.cls != cls || !seenBy(view, m)) continue;
      if (cls == ReflectionClass::OffScreen && m.screen.z > 0 && m.screen.x > -2 && m.screen.y > -2 &&
          m.screen.x < g.width + 2 && m.screen.y < g.height + 2)
        continue;
      ++s.pixels;
      const float a = pass.reflection.at(x, y, 3);
      for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(pass.reflection.at(x, y, c)));
      s.found += a > 0.0f;
      s.exact += a > 0.99f && maxAbsDiff(m.color, pass.reflection, x, y) <= kColorTol + m.colorSpread;
      s.fromView += !pass.view.empty() && pass.view.at(x, y, 0) == 1.0f && pass.view.at(x, y, 1) == 1.0f;
    }
  return s;
}

// A pass `ssrcl trace` or `ssrcl batch` wrote, with its view channels.
Pass readPass(const std::string& exr) {
  const ExrContents out = readExr(exr);
  Pass pass{ssrcl::Image(out.width, out.height, 4), ssrcl::Image(out.width, out.height, 2)};
  const char* rgba[] = {"R", "G", "B", "A"};
  for (size_t i = 0; i < size_t(out.width) * out.height; ++i) {
    for (int c = 0; c < 4; ++c) pass.reflection.data[4 * i + c] = out.channels.at(rgba[c]).values[i];
    pass.view.data[2 * i] = out.channels.at("view").values[i];
    pass.view.data[2 * i + 1] = out.channels.at("view_share").values[i];
  }
  return pass;
}

struct WithAndWithout {
  Score with, without;
};

// The frame (480x270) and one 960x540 view of `scene`, traced with and without the view, scored
// over the frame's pixels of class `cls` whose hit the view sees.
WithAndWithout compare(const Scene& scene, const ViewParams& frameParams, const ViewParams& viewParams,
                       ReflectionClass cls, ssrcl::ViewTime time = ssrcl::ViewTime::Same) {
  const ssrcl::Camera camera = makeCamera(frameParams, 480, 270);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const MirrorTruth truth = exactMirrorReflection(scene, camera, g);
  const View view = renderView(scene, viewParams, 960, 540);
  return {score(g, truth, cls, view, trace(g, camera, {&view}, time)),
          score(g, truth, cls, view, trace(g, camera, {}))};
}

// The mirror floor seen through a narrow lens reflects the spheres' tops, above the frame; a wide
// view from the same eye shows them.
TEST(Multiview, OffScreenReflectionsComeFromAWideView) {
  const Scene scene = makeScene("spheres_on_mirror");
  const auto [frameParams, wideParams] = narrowAndWide(scene);
  const auto [with, without] = compare(scene, frameParams, wideParams, ReflectionClass::OffScreen);
  std::cout << "off-screen hits the wide view sees: " << with.pixels << "; with it exact " << with.fraction(with.exact)
            << ", from the view " << with.fraction(with.fromView) << "; without it found "
            << without.fraction(without.found) << "\n";
  ASSERT_GT(with.pixels, 1000u);  // the scene is meant to have them
  // Measured 0.975 exact and 0.988 from the view (1,586 pixels): the rest sit at silhouettes.
  EXPECT_GE(with.fraction(with.exact), 0.97);
  EXPECT_GE(with.fraction(with.fromView), 0.98);
  // A = 0 where the frame cannot see the hit: measured 2 of 1,586 pixels with A > 0, at silhouettes
  // where the frame's neighbouring surface is taken.
  EXPECT_LE(without.fraction(without.found), 0.005);
}

// View hits keep at most TraceSettings::viewRadianceCap times the frame's 99th percentile of
// brightness: the spheres' tops the wide view shows are no brighter than the frame's own surfaces,
// so the default cap (2) and none (0) leave them exact; a cap of 0.05 dims every one.
TEST(Multiview, TheViewCapDimsOnlyWhatIsBrighterThanItAllows) {
  const Scene scene = makeScene("spheres_on_mirror");
  const auto [frameParams, wideParams] = narrowAndWide(scene);
  const ssrcl::Camera camera = makeCamera(frameParams, 240, 135);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const MirrorTruth truth = exactMirrorReflection(scene, camera, g);
  const View wide = renderView(scene, wideParams, 480, 270);
  const auto exact = [&](float cap) {
    const Pass pass = trace(g, camera, {&wide}, ssrcl::ViewTime::Same, cap);
    const Score s = score(g, truth, ReflectionClass::OffScreen, wide, pass);
    EXPECT_GT(s.pixels, 200u);
    return s.fraction(s.exact);
  };
  const double capped = exact(2.0f), none = exact(0.0f), dimmed = exact(0.05f);
  std::cout << "off-screen hits exact: cap 2 " << capped << ", none " << none << ", 0.05 " << dimmed << "\n";
  EXPECT_GE(capped, 0.9);
  EXPECT_EQ(none, capped);
  EXPECT_LE(dimmed, 0.05);
}

// The views' rays in packets (kernels/view_trace.cl, trace.cl trace_round) find what trace_hiz
// finds a ray at a time, to the bit.
TEST(Multiview, PacketsTraceAsTheScalarHiZ) {
  const Scene scene = makeScene("spheres_on_mirror");
  const auto [frameParams, wideParams] = narrowAndWide(scene);
  const View frame = renderView(scene, frameParams, 160, 90), wide = renderView(scene, wideParams, 160, 90);
  auto run = [&](const char* options) {
    const ssrcl::test::ScopedEnv env("SSRCL_KERNEL_BUILD_OPTIONS", options);
    return trace(frame.g, frame.camera, {&wide});
  };
  const Pass packets = run("-DSSRCL_TRACE_SCALAR=0"), scalar = run("-DSSRCL_TRACE_SCALAR=1");
  ASSERT_EQ(packets.reflection.data.size(), scalar.reflection.data.size());
  size_t differ = 0, fromView = 0;
  for (size_t i = 0; i < packets.reflection.data.size(); ++i)
    differ += std::memcmp(&packets.reflection.data[i], &scalar.reflection.data[i], sizeof(float)) != 0;
  for (size_t i = 0; i < packets.view.data.size(); ++i) {
    differ += std::memcmp(&packets.view.data[i], &scalar.view.data[i], sizeof(float)) != 0;
    fromView += packets.view.data[i] > 0.0f;
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(fromView, 100u);  // the view's rays are taken
}

// The same through `ssrcl batch --view`: two frames of the narrow lens (the second orbited by 2
// degrees) share one wide view; in each frame's output the off-screen hits the view sees are exact.
TEST(Multiview, BatchWithAStaticViewGivesTheExactOffScreenReflection) {
  const Scene scene = makeScene("spheres_on_mirror");
  ssrcl::test::TempDir dir{"ssrcl-multiview-batch"};
  AnalyticSequence frames, wide;
  frames.directory = wide.directory = dir.path().string();
  frames.frameCount = 2;
  frames.width = 480;
  frames.height = 270;
  frames.fovYDegrees = 30.0;
  wide.prefix = "wide";
  wide.frameCount = 1;
  wide.width = 960;
  wide.height = 540;
  wide.fovYDegrees = 75.0;
  const std::string pattern = writeAnalyticSequence(frames);
  writeAnalyticSequence(wide);
  const auto r = runCommand(shellQuote(SSRCL_CLI) + " batch " + shellQuote(pattern) + " -o " +
                            shellQuote(dir.file("out") + "/") + " --edge-fade 0 --view " +
                            shellQuote(dir.file("wide.1001.exr")));  // the truth has no fade
  ASSERT_EQ(r.exitCode, 0) << r.output;

  View view;
  view.camera = ssrcl::loadCameraJson(dir.file("wide.1001.camera.json"));
  view.g = renderGBuffer(scene, view.camera);
  for (const std::string frame : {"1001", "1002"}) {
    const ssrcl::Camera camera = ssrcl::loadCameraJson(dir.file("shot." + frame + ".camera.json"));
    const AnalyticGBuffer g = renderGBuffer(scene, camera);
    const Pass pass = readPass(dir.file("out/shot." + frame + ".refl.exr"));
    const Score with = score(g, exactMirrorReflection(scene, camera, g), ReflectionClass::OffScreen, view, pass);
    std::cout << "frame " << frame << ": off-screen hits the wide view sees " << with.pixels << ", exact "
              << with.fraction(with.exact) << ", from the view " << with.fraction(with.fromView) << "\n";
    ASSERT_GT(with.pixels, 1000u);
    // As through the library (OffScreenReflectionsComeFromAWideView), from the batch's half-float
    // outputs: measured 0.975 and 0.973 exact, 0.989 and 0.991 from the view (1,586 and 1,605 pixels).
    EXPECT_GE(with.fraction(with.exact), 0.97);
    EXPECT_GE(with.fraction(with.fromView), 0.98);
  }
}

// Mirror rays that meet a surface another one hides from the frame (spheres reflecting each
// other's far sides): the frame's hits there are the surfaces in front, taken within their
// thickness or found after the ray passed behind one. A view from the other side sees them.
TEST(Multiview, HiddenReflectionsComeFromAViewThatSeesThem) {
  const Scene scene = makeScene("spheres_on_mirror");
  ViewParams reverseParams = scene.view;
  reverseParams.eye = dvec3(0.0, 4.5, -8.5);
  reverseParams.fovYDegrees = 60.0;
  const auto [with, without] = compare(scene, scene.view, reverseParams, ReflectionClass::Occluded);
  std::cout << "hidden hits the reverse view sees: " << with.pixels << "; exact with it " << with.fraction(with.exact)
            << ", without " << without.fraction(without.exact) << " (found " << without.fraction(without.found)
            << ")\n";
  ASSERT_GT(with.pixels, 300u);
  // Measured 0.810 with the view (591 pixels), 0.027 without; 0.777 while the views stepped behind
  // surfaces pixel by pixel, 0.761 where the range pyramid's skip forgets that the ray passed
  // behind them (passed_cell, kernels/trace.cl). A view replaces a frame's doubtful hit only when
  // it sees the ray's whole way (kernels/view_trace.cl); the rest pass behind another surface in
  // the view too. Taking every view hit gives 0.948 here but -1.9 dB on the corpus's bump_floor
  // (contact points hidden from every view took emitters seen past them).
  EXPECT_GE(with.fraction(with.exact), 0.79);
  EXPECT_LE(without.fraction(without.exact), 0.05);
}

// The same from a neighbouring frame (ViewTime::Other) of the static scene: the hidden surfaces it
// sees lie behind what the frame shows, so none counts as moved. These rays miss or hit in the
// frame after passing behind the spheres' fronts (facing them or not): not clear misses, which a
// neighbour takes up only past the frame's frustum (kernels/view_trace.cl), so it traces them whole.
TEST(Multiview, HiddenReflectionsComeFromANeighbouringFrameToo) {
  const Scene scene = makeScene("spheres_on_mirror");
  ViewParams reverseParams = scene.view;
  reverseParams.eye = dvec3(0.0, 4.5, -8.5);
  reverseParams.fovYDegrees = 60.0;
  const auto [with, without] =
      compare(scene, scene.view, reverseParams, ReflectionClass::Occluded, ssrcl::ViewTime::Other);
  std::cout << "hidden hits the reverse neighbour sees: " << with.pixels << "; exact with it "
            << with.fraction(with.exact) << "\n";
  ASSERT_GT(with.pixels, 300u);
  EXPECT_GE(with.fraction(with.exact), 0.79);  // measured 0.810, as from a view of the same moment
}

// Views that add nothing leave the pass as it was, and removing them restores it bit for bit.
TEST(Multiview, ClearedViewsGiveTheSinglePassBitForBit) {
  const Scene scene = makeScene("spheres_on_mirror");
  const ssrcl::Camera camera = makeCamera(scene.view, 160, 90);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const View same = renderView(scene, scene.view, 160, 90);
  ssrcl::Device device = testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(g);
  p.setCamera(camera);
  p.commit();
  p.execute();
  const ssrcl::Image single = p.output("reflection");
  EXPECT_TRUE(p.output("view").empty());
  p.setView(0, same.g, same.camera);
  p.commit();
  p.execute();
  EXPECT_EQ(p.output("view").channels, 2);
  p.clearViews();
  p.commit();
  p.execute();
  EXPECT_EQ(p.output("reflection").data, single.data);
  EXPECT_TRUE(p.output("view").empty());
}

// The sliding window's premise: replacing one view leaves the others' device images as they
// were prepared. After view 0's colour is blacked out in memory, replacing view 1 gives the same
// pass (view 0 was not read again); replacing view 0 shows the black (so the test can fail).
TEST(Multiview, ReplacingAViewLeavesTheOthersPrepared) {
  const Scene scene = makeScene("spheres_on_mirror");
  const auto [frameParams, wideParams] = narrowAndWide(scene);
  const ssrcl::Camera camera = makeCamera(frameParams, 160, 90);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  View wide = renderView(scene, wideParams, 320, 180);
  const View same = renderView(scene, frameParams, 160, 90);
  ssrcl::Device device = testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(g);
  p.setCamera(camera);
  p.setView(0, wide.g, wide.camera);
  p.setView(1, same.g, same.camera);
  p.commit();
  p.execute();
  const ssrcl::Image prepared = p.output("reflection");
  std::fill(wide.g.color.data.begin(), wide.g.color.data.end(), 0.0f);
  p.setView(1, same.g, same.camera);
  p.commit();
  p.execute();
  EXPECT_EQ(p.output("reflection").data, prepared.data);
  p.setView(0, wide.g, wide.camera);
  p.commit();
  p.execute();
  EXPECT_NE(p.output("reflection").data, prepared.data);
}

TEST(Multiview, BadViewsAreNamed) {
  const Scene scene = makeScene("spheres_on_mirror");
  const ssrcl::Camera camera = makeCamera(scene.view, 64, 36);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  View wrong = renderView(scene, scene.view, 64, 36);
  wrong.camera.width = 50;  // the images are 64 wide
  ssrcl::Device device = testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(g);
  p.setCamera(camera);
  p.setView(0, wrong.g, wrong.camera, "side.exr");
  try {
    p.commit();
    FAIL() << "a view whose images are not its camera's size was accepted";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidInput);
    EXPECT_NE(std::string(e.what()).find("side.exr"), std::string::npos) << e.what();
  }
  EXPECT_THROW(p.setView(2, wrong.g, wrong.camera), ssrcl::Error);  // indices are contiguous
}

// A frame too large for the device, with views: the out-of-memory error lists them with their
// sizes, since they share the device memory. The frame's images are views of one small buffer:
// commit() checks the memory before it reads a pixel.
TEST(Multiview, OutOfMemoryNamesTheViews) {
  const Scene scene = makeScene("spheres_on_mirror");
  const View side = renderView(scene, scene.view, 64, 36), back = renderView(scene, scene.view, 32, 18);
  const int size = 32768;  // 1 Gi pixels, the most a frame may have: 16 GiB for the output's RGBA alone
  std::vector<float> pixel(4, 0.0f);
  const auto huge = [&](int channels) { return ssrcl::ImageView(pixel.data(), size, size, channels); };
  ssrcl::Device device = testDevice();
  ssrcl::Pipeline p(device);
  p.setImage("color", huge(3));
  p.setImage("depth", huge(1));
  p.setImage("normal", huge(3));
  p.setImage("roughness", huge(1));
  p.setCamera(makeCamera(scene.view, size, size));
  p.setView(0, side.g, side.camera, "side.exr");
  p.setView(1, back.g, back.camera);
  try {
    p.commit();
    FAIL() << "a 32768x32768 frame fitted";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::OutOfMemory) << e.what();
    const std::string m = e.what();
    EXPECT_NE(m.find("32768x32768 frame with views side.exr (64x36), view 2 (32x18)"), std::string::npos) << m;
  }
}

// A narrow lens (30 degrees) dollying back from spheres_on_mirror, `dolly` units a frame.
AnalyticSequence dollySequence(const std::string& directory, int frames, int width, int height, double dolly) {
  AnalyticSequence sequence;
  sequence.directory = directory;
  sequence.frameCount = frames;
  sequence.width = width;
  sequence.height = height;
  sequence.fovYDegrees = 30.0;
  sequence.degreesPerFrame = 0.0;
  sequence.dollyPerFrame = dolly;
  return sequence;
}

// Neighbouring frames as views (`ssrcl batch --neighbours`): a narrow lens dollying back from
// spheres_on_mirror, 4 units a frame over three frames, each frame the others' neighbours. The
// first frame's floor reflects the spheres' tops above it; the later frames, further back, see
// them. Traced once (edge fade 0: the truth has none) for the tests below.
struct NeighbourShot {
  TempDir dir{"ssrcl-neighbours"};
  AnalyticSequence sequence;
  std::string pattern;
  CommandResult batch;
  NeighbourShot() {
    sequence = dollySequence(dir.path().string(), 3, 480, 270, 4.0);
    pattern = writeAnalyticSequence(sequence);
    batch = runCommand(shellQuote(SSRCL_CLI) + " batch " + shellQuote(pattern) + " -o " +
                       shellQuote(dir.file("out") + "/") + " --edge-fade 0 --neighbours 1");
  }
  std::string frame(int k) const { return dir.file("shot.100" + std::to_string(k + 1) + ".exr"); }
  std::string output(int k) const { return dir.file("out/shot.100" + std::to_string(k + 1) + ".refl.exr"); }
};

const NeighbourShot& neighbourShot() {
  static const NeighbourShot shot;
  return shot;
}

// The first frame's off-screen hits that the last frame sees come out exact, from the views.
TEST(Neighbours, OffScreenReflectionsComeFromLaterFramesOfADolly) {
  const NeighbourShot& shot = neighbourShot();
  ASSERT_EQ(shot.batch.exitCode, 0) << shot.batch.output;
  const Scene scene = sequenceScene(shot.sequence);
  const ssrcl::Camera camera = sequenceCamera(shot.sequence, 0);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  View last;
  last.camera = sequenceCamera(shot.sequence, 2);
  last.g = renderGBuffer(scene, last.camera);
  const MirrorTruth truth = exactMirrorReflection(scene, camera, g);
  const Score with = score(g, truth, ReflectionClass::OffScreen, last, readPass(shot.output(0)));
  const Score without = score(g, truth, ReflectionClass::OffScreen, last, trace(g, camera, {}));
  std::cout << "off-screen hits the last frame sees: " << with.pixels << "; with neighbours exact "
            << with.fraction(with.exact) << ", found " << with.fraction(with.found) << "; without found "
            << without.fraction(without.found) << "\n";
  ASSERT_GT(with.pixels, 1000u);
  EXPECT_GE(with.fraction(with.exact), 0.95);
  EXPECT_LE(without.fraction(without.found), 0.005);
}

// A batch frame is `ssrcl trace` of that frame with its neighbours given as --neighbour, bit for
// bit: the same views, the same rejection of moved hits. The middle frame's views are the first
// and the last frame, in that order (the first frame's window put the last frame in view 2).
TEST(Neighbours, BatchFrameEqualsTraceWithTheNeighbours) {
  const NeighbourShot& shot = neighbourShot();
  ASSERT_EQ(shot.batch.exitCode, 0) << shot.batch.output;
  const std::string traced = shot.dir.file("middle.refl.exr");
  const auto r = runCommand(shellQuote(SSRCL_CLI) + " trace " + shellQuote(shot.frame(1)) + " -o " +
                            shellQuote(traced) + " --edge-fade 0 --neighbour " + shellQuote(shot.frame(0)) +
                            " --neighbour " + shellQuote(shot.frame(2)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const ExrContents batch = readExr(shot.output(1)), single = readExr(traced);
  for (const char* channel : {"R", "G", "B", "A", "distance", "view", "view_share"})
    EXPECT_EQ(batch.channels.at(channel).values, single.channels.at(channel).values) << channel;
  double share = 0;
  for (float v : batch.channels.at("view_share").values) share += v;
  EXPECT_GT(share, 100.0);  // the views did supply hits
}

// An object that moved: in the neighbour the cyan box hangs in the air in front of the camera
// (thrown), in the frame it stands far to the right, off screen. Floor rays that escape to the
// sky in the frame meet it in the neighbour; taken from a view of the same moment
// (ViewTime::Same) they show it, from a neighbouring frame (ViewTime::Other) they do not: the
// frame shows the floor well behind where the neighbour puts the box, so it has moved, and those
// pixels keep the frame's own pass, bit for bit. (These rays leave the frame clear, in front of
// everything: a neighbouring frame takes them up only past the frame's frustum, so the box is
// not even traced; a ray that passed behind a surface is traced whole and refused by
// view_trace.cl's moved_since.)
TEST(Neighbours, AMovedObjectIsNotTakenFromANeighbour) {
  const Scene scene = makeScene("spheres_on_mirror");
  Scene moved = scene;
  int box = -1;
  for (size_t k = 0; k < moved.primitives.size(); ++k)
    if (moved.primitives[k].name == "cyan_box") box = int(k);
  ASSERT_GE(box, 0);
  moved.primitives[size_t(box)].center = dvec3(1.5, 1.2, 1.5);  // its base 0.6 above the floor
  ViewParams frameParams = scene.view, wideParams = scene.view;
  frameParams.fovYDegrees = 30.0;
  wideParams.fovYDegrees = 60.0;
  const ssrcl::Camera camera = makeCamera(frameParams, 480, 270);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const View neighbour = renderView(moved, wideParams, 960, 540);
  const MirrorTruth now = exactMirrorReflection(scene, camera, g), then = exactMirrorReflection(moved, camera, g);
  const Pass alone = trace(g, camera, {}), same = trace(g, camera, {&neighbour}, ssrcl::ViewTime::Same),
             other = trace(g, camera, {&neighbour}, ssrcl::ViewTime::Other);
  size_t pixels = 0, takenSame = 0, unchanged = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      if (now.at(x, y).cls != ReflectionClass::Sky || then.at(x, y).hit.primitive != box) continue;
      ++pixels;
      takenSame += same.reflection.at(x, y, 3) > 0.5f;
      bool equal = true;
      for (int c = 0; c < 4; ++c) equal = equal && other.reflection.at(x, y, c) == alone.reflection.at(x, y, c);
      unchanged += equal;
    }
  std::cout << "frame pixels whose sky rays meet the moved box in the neighbour: " << pixels
            << "; taken from a same-moment view " << takenSame << ", unchanged with a neighbouring frame "
            << unchanged << "\n";
  ASSERT_GT(pixels, 200u);
  // The test can fail: a view of the same moment takes the box. Measured 1,350 of 3,190 pixels:
  // the others meet its underside, which the view does not show.
  EXPECT_GE(double(takenSame) / pixels, 0.35);
  EXPECT_EQ(unchanged, pixels);  // measured: all 3,190
}

// `--neighbour-reach`: neighbours far apart in the shot show what lies past the frame's edges,
// where adjacent frames add little. A camera dollying back over five frames: the first frame's
// neighbours reaching 4 frames out are the last two (its shot has no frame before it), whose wider
// views see more of what its rays leave the screen for than frames 2 and 3 do; the batch frame is
// `ssrcl trace` with those two as --neighbour, bit for bit.
TEST(Neighbours, FartherNeighboursShowMoreOfWhatLiesOffScreen) {
  TempDir dir{"ssrcl-neighbour-reach"};
  const AnalyticSequence sequence = dollySequence(dir.path().string(), 5, 240, 135, 1.0);
  const std::string pattern = writeAnalyticSequence(sequence);
  const auto frame = [&](int k) { return dir.file("shot.100" + std::to_string(k + 1) + ".exr"); };
  const auto batch = [&](const std::string& out, int reach) {
    const auto r = runCommand(shellQuote(SSRCL_CLI) + " batch " + shellQuote(pattern) + " -o " +
                              shellQuote(dir.file(out) + "/") + " --temporal 0 --neighbours 1 --neighbour-reach " +
                              std::to_string(reach));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readPass(dir.file(out + "/shot.1001.refl.exr"));
  };
  const Pass adjacent = batch("adjacent", 1), far = batch("far", 4);
  const Scene scene = sequenceScene(sequence);
  const ssrcl::Camera camera = sequenceCamera(sequence, 0);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  View last;
  last.camera = sequenceCamera(sequence, 4);
  last.g = renderGBuffer(scene, last.camera);
  const MirrorTruth truth = exactMirrorReflection(scene, camera, g);
  const Score near = score(g, truth, ReflectionClass::OffScreen, last, adjacent),
              wide = score(g, truth, ReflectionClass::OffScreen, last, far);
  std::cout << "off-screen hits the last frame sees: " << near.pixels << "; exact with frames 2-3 "
            << near.fraction(near.exact) << ", with frames 4-5 " << wide.fraction(wide.exact) << "\n";
  ASSERT_GT(near.pixels, 250u);
  // Measured 314 pixels: 81.8% exact with frames 2-3, 95.9% with frames 4-5.
  EXPECT_GE(wide.fraction(wide.exact), 0.93);
  EXPECT_GE(wide.fraction(wide.exact), near.fraction(near.exact) + 0.1);

  const std::string traced = dir.file("traced.exr");
  const auto r = runCommand(shellQuote(SSRCL_CLI) + " trace " + shellQuote(frame(0)) + " -o " + shellQuote(traced) +
                            " --neighbour " + shellQuote(frame(3)) + " --neighbour " + shellQuote(frame(4)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const ExrContents fromBatch = readExr(dir.file("far/shot.1001.refl.exr")), single = readExr(traced);
  for (const char* channel : {"R", "G", "B", "A", "distance", "view", "view_share"})
    EXPECT_EQ(fromBatch.channels.at(channel).values, single.channels.at(channel).values) << channel;
  const auto bad = runCommand(shellQuote(SSRCL_CLI) + " batch " + shellQuote(pattern) + " -o " +
                              shellQuote(dir.file("bad") + "/") + " --neighbours 2 --neighbour-reach 1");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--neighbour-reach 1: must be at least --neighbours (2)"), std::string::npos) << bad.output;
}

// Views are inputs: resuming the batch with other neighbours refuses the outputs made with these;
// the same neighbours skip them.
TEST(Neighbours, ResumingComparesTheViews) {
  const NeighbourShot& shot = neighbourShot();
  ASSERT_EQ(shot.batch.exitCode, 0) << shot.batch.output;
  const std::string batch = shellQuote(SSRCL_CLI) + " batch " + shellQuote(shot.pattern) + " -o " +
                            shellQuote(shot.dir.file("out") + "/") + " --edge-fade 0";
  const auto same = runCommand(batch + " --neighbours 1");
  EXPECT_EQ(same.exitCode, 0) << same.output;
  EXPECT_NE(same.output.find("3 skipped"), std::string::npos) << same.output;
  const auto none = runCommand(batch + " --neighbours 0");
  EXPECT_EQ(none.exitCode, 2) << none.output;
  EXPECT_NE(none.output.find("shot.1001.refl.exr: exists with views '"), std::string::npos) << none.output;
  EXPECT_NE(none.output.find("but none is asked now; give --overwrite"), std::string::npos) << none.output;
}

// A shard's frames have the whole run's views, in the same order, however many frames went before
// in either: with 16 frames the default windows (one neighbour each side, 12 frames out) differ
// between runs that start at frame 1 and at a shard's first frame; the views' order decides the
// `view` channel and how sums over views round. Every output equals the whole run's, bit for bit.
TEST(Neighbours, ShardsHaveTheWholeRunsViewsInOrder) {
  TempDir dir{"ssrcl-neighbour-shards"};
  AnalyticSequence sequence;
  sequence.directory = dir.file("in");
  sequence.frameCount = 16;
  sequence.roughness = 0.3;
  const std::string batch =
      shellQuote(SSRCL_CLI) + " batch " + shellQuote(writeAnalyticSequence(sequence)) + " -q --neighbours 1 -o ";
  ASSERT_EQ(runCommand(batch + shellQuote(dir.file("whole") + "/")).exitCode, 0);
  for (int shard = 0; shard < 8; ++shard) {
    const auto r = runCommand(batch + shellQuote(dir.file("shards") + "/") + " --shard " + std::to_string(shard) + "/8");
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  for (int frame = 1001; frame <= 1016; ++frame) {
    const std::string name = "/shot." + std::to_string(frame) + ".refl.exr";
    EXPECT_EQ(readBytes(dir.file("shards") + name), readBytes(dir.file("whole") + name)) << name;
  }
}

TEST(Neighbours, BadCountsAndMissingCamerasAreNamed) {
  const NeighbourShot& shot = neighbourShot();
  const std::string batch = shellQuote(SSRCL_CLI) + " batch " + shellQuote(shot.pattern) + " --overwrite -o " +
                            shellQuote(shot.dir.file("bad") + "/");
  const auto negative = runCommand(batch + " --neighbours -1");
  EXPECT_EQ(negative.exitCode, 2) << negative.output;
  EXPECT_NE(negative.output.find("--neighbours -1: must be 0 or more"), std::string::npos) << negative.output;
  const auto large = runCommand(batch + " --neighbours 2");
  EXPECT_EQ(large.exitCode, 2) << large.output;
  EXPECT_NE(large.output.find("--neighbours 2 needs at least 5 frames in the sequence, it has 3"), std::string::npos)
      << large.output;
  const auto huge = runCommand(batch + " --neighbours 2000000000");
  EXPECT_EQ(huge.exitCode, 2) << huge.output;
  EXPECT_NE(huge.output.find("--neighbours 2000000000 with 0 --view: 4000000000 views, at most 16"), std::string::npos)
      << huge.output;
  // The last frame without its camera (nor one in its header): the frames whose window holds it fail, naming it.
  TempDir dir{"ssrcl-neighbours-camera"};
  for (int k = 0; k < 3; ++k) {
    const std::string name = "shot.100" + std::to_string(k + 1);
    std::filesystem::copy_file(shot.dir.file(name + ".exr"), dir.file(name + ".exr"));
    if (k < 2) std::filesystem::copy_file(shot.dir.file(name + ".camera.json"), dir.file(name + ".camera.json"));
  }
  const auto missing = runCommand(shellQuote(SSRCL_CLI) + " batch " + shellQuote(dir.file("shot.####.exr")) +
                                  " -o " + shellQuote(dir.file("out") + "/") + " --neighbours 1");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("frame 1001: neighbour " + dir.file("shot.1003.exr") + ": "), std::string::npos)
      << missing.output;
}

}  // namespace
