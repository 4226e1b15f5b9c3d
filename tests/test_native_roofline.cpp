// The OpenCL mirror pass against the native C++ implementation of the same rays
// (bench/native_mirror_trace, the roofline of bench/ssrcl_roofline): written separately from
// the kernels, same float arithmetic, so every pixel's hit must agree but for float ties. The
// native min-max packet trace (bench/packet_hiz_trace, 16 rays in AVX-512 lanes or 8 in AVX2,
// whichever the CPU has; hit test on depth alone) against a half-pixel linear march of the same depth buffer. The
// native stages before the trace (bench/native_frame_stages) against the library's (bench/device_frame_stages).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "device_frame_stages.hpp"
#include "native_mirror_trace.hpp"
#include "packet_hiz_trace.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/test_device.hpp"

namespace {

class NativeRoofline : public testing::TestWithParam<const char*> {
 protected:
  const ssrcl::test::Scene scene = ssrcl::test::makeScene(GetParam());
  const ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, 320, 180);
  const ssrcl::GBuffer g = ssrcl::test::renderGBuffer(scene, camera);
  const ssrcl::TraceSettings settings = ssrcl::bench::nativeMirrorSettings();
};

void expectAgreement(const ssrcl::bench::HitAgreement& hits) {
  ASSERT_GT(hits.hitPixels, 1000);  // the scene reflects something: the comparison means something
  EXPECT_LE(hits.disagreeing, hits.hitPixels / 1000) << hits.disagreeing << " of " << hits.hitPixels;
}

TEST_P(NativeRoofline, HitsAgreeWithOpenCl) {
  ssrcl::Pipeline p(ssrcl::test::testDevice());
  p.setGBuffer(g);
  p.setCamera(camera);
  p.settings() = settings;
  p.commit();
  p.execute();
  ssrcl::bench::NativeMirrorTrace native(g, camera, settings);
  native.run(2);

  EXPECT_EQ(native.rays(), p.stageTimes().tracedRays);
  expectAgreement(ssrcl::bench::compareHitDistances(native.distance(), p.output("distance").data));
}

// The same samples as the march (a quarter pixel off the pixel boundaries): the same hit points.
TEST_P(NativeRoofline, PacketHitsAgreeWithLinearMarch) {
  if (!ssrcl::bench::packetTraceSupported()) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  ssrcl::bench::NativeMirrorTrace native(g, camera, settings);
  native.run(2);
  native.runLinearMarch(2);
  for (const auto format : {ssrcl::bench::TexelFormat::Half, ssrcl::bench::TexelFormat::Float}) {
    native.setPacketTexels(format);
    native.runPackets(2);
    EXPECT_EQ(native.packetStats().rays, native.rays());
    expectAgreement(ssrcl::bench::compareHitPoints(native.packetHitPoints(), native.linearHitPoints(), 0.01f));
  }
}

// Where the CPU has AVX-512 the AVX2 trace runs too, and traces the same rays to the same hits.
TEST_P(NativeRoofline, Avx2PacketsHitAsAvx512Packets) {
  if (ssrcl::bench::packetTraceIsa() != ssrcl::bench::PacketIsa::Avx512) GTEST_SKIP() << "this CPU has no AVX-512";
  ssrcl::bench::NativeMirrorTrace native(g, camera, settings);
  native.run(2);
  native.runPackets(2);
  const std::vector<float> wide = native.packetHitPoints();
  native.setPacketIsa(ssrcl::bench::PacketIsa::Avx2);
  native.runPackets(2);
  expectAgreement(ssrcl::bench::compareHitPoints(native.packetHitPoints(), wide, 0.01f));
}

// GGX samples of a surface of roughness 0 are its mirror ray (alpha clamped to 1e-4: within a
// hundredth of a degree): 4 a pixel, hitting as the mirror rays do.
TEST_P(NativeRoofline, GlossyRaysOfAMirrorHitAsItsMirrorRay) {
  if (!ssrcl::bench::packetTraceSupported()) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  ssrcl::bench::NativeMirrorTrace native(g, camera, settings);
  native.run(2);
  native.runPackets(2);
  const ssrcl::bench::PacketStats mirror = native.packetStats();
  native.runGlossyPackets(2, 4);
  const ssrcl::bench::PacketStats glossy = native.packetStats();
  ASSERT_GT(mirror.hits, 1000);
  EXPECT_EQ(glossy.rays, 4 * mirror.rays);
  EXPECT_NEAR(double(glossy.hits), 4.0 * double(mirror.hits), 0.01 * 4.0 * double(mirror.hits));
}

// Elements of a and b (float vectors) that differ: an infinity against anything else, or any
// component by more than `relative` of the elements' largest finite component.
template <class V>
long long differing(const std::vector<V>& a, const std::vector<V>& b, float relative) {
  EXPECT_EQ(a.size(), b.size());
  long long count = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    float scale = 0.0f;
    for (int c = 0; c < V::length(); ++c)
      for (float v : {a[i][c], b[i][c]})
        if (std::isfinite(v)) scale = std::max(scale, std::fabs(v));
    bool differs = false;
    for (int c = 0; c < V::length(); ++c) {
      const float u = a[i][c], v = b[i][c];
      differs |= std::isfinite(u) && std::isfinite(v) ? !(std::fabs(u - v) <= relative * scale) : u != v;
    }
    count += differs;
  }
  return count;
}

// Setup, HZB, adaptive thickness, range and colour pyramids: the same outputs but for float
// rounding. A thickness run can end on a float tie (a neighbour joined within 2% of the depth
// or not), which changes its pixels' planes: a thousandth of them may differ.
TEST_P(NativeRoofline, FrameStagesAgreeWithOpenCl) {
  ssrcl::TraceSettings s = settings;
  s.thicknessModel = ssrcl::ThicknessModel::Adaptive;
  s.constantRoughness.reset();
  ssrcl::GBuffer mixed = g;  // colour weights 0 (specular) and 1 (rough) in the colour pyramid
  mixed.roughness = ssrcl::Image(camera.width, camera.height, 1);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) mixed.roughness.at(x, y, 0) = (x * 7 + y * 3) % 5 == 0 ? 0.5f : 0.95f;
  ssrcl::bench::DeviceFrameStages device(ssrcl::test::testDevice(), mixed, camera, s);
  device.run();
  ssrcl::bench::NativeMirrorTrace native(mixed, camera, s);
  native.run(2);  // setup's planes before the thickness stage
  const std::vector<glm::vec4> setupPlanes = native.planes();
  native.runFrame(2);

  const long long pixels = camera.width * camera.height;
  std::vector<glm::vec1> nativeHzb, deviceHzb;
  for (float d : native.hzb()) nativeHzb.emplace_back(d);
  for (float d : device.hzb()) deviceHzb.emplace_back(d);
  EXPECT_EQ(differing(nativeHzb, deviceHzb, 1e-5f), 0);
  // The thickness stage changed the planes: the comparison below is of its work.
  EXPECT_GT(differing(native.planes(), setupPlanes, 1e-3f), pixels / 4);
  EXPECT_LE(differing(native.planes(), device.planes(), 1e-4f), pixels / 1000);
  EXPECT_LE(differing(native.rangePyramid(), device.rangePyramid(), 1e-4f), pixels / 1000);
  const std::vector<glm::vec4> colors = native.colorPyramid();
  EXPECT_GT(std::count_if(colors.begin() + pixels, colors.end(), [](glm::vec4 c) { return c.w > 0.0f && c.w < 1.0f; }),
            0);  // coarse texels mix weights 0 and 1
  EXPECT_EQ(differing(colors, device.colorPyramid(), 1e-5f), 0);
  // Edge colours ran: beside the nearer objects' edges hits read other colours than as written.
  ssrcl::TraceSettings asWritten = s;
  asWritten.edgeColors = false;
  ssrcl::bench::NativeMirrorTrace plain(mixed, camera, asWritten);
  plain.runFrame(2);
  EXPECT_GT(differing(colors, plain.colorPyramid(), 1e-5f), 0);
}

// The lane operations of the CPU's packet trace (and of the AVX2 one on an AVX-512 CPU), every
// mask and table index: a wrong lane moves too few hits for the tests above to see.
TEST(PacketLanes, OperationsDoInEveryLaneWhatTheyMean) {
  const ssrcl::bench::PacketIsa isa = ssrcl::bench::packetTraceIsa();
  if (isa == ssrcl::bench::PacketIsa::None) GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  const char* avx2 = ssrcl::bench::packetLaneOpsErrorAvx2();
  EXPECT_TRUE(avx2 == nullptr) << "AVX2 " << avx2;
  if (isa != ssrcl::bench::PacketIsa::Avx512) return;
  const char* avx512 = ssrcl::bench::packetLaneOpsErrorAvx512();
  EXPECT_TRUE(avx512 == nullptr) << "AVX-512 " << avx512;
}

INSTANTIATE_TEST_SUITE_P(Scenes, NativeRoofline, testing::Values("spheres_on_mirror", "mirror_wall", "half_sky"));

}  // namespace
