// The OpenCL mirror pass against the native C++ implementation of the same rays
// (bench/native_mirror_trace, the roofline of bench/ssrcl_roofline): written separately from
// the kernels, same float arithmetic, so every pixel's hit must agree but for float ties. The
// native min-max packet trace (bench/packet_hiz_trace, 16 rays in AVX-512 lanes, hit test on
// depth alone) against a half-pixel linear march of the same depth buffer.
#include <gtest/gtest.h>

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
  if (!ssrcl::bench::packetTraceSupported()) GTEST_SKIP() << "this CPU has no AVX-512";
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

// GGX samples of a surface of roughness 0 are its mirror ray (alpha clamped to 1e-4: within a
// hundredth of a degree): 4 a pixel, hitting as the mirror rays do.
TEST_P(NativeRoofline, GlossyRaysOfAMirrorHitAsItsMirrorRay) {
  if (!ssrcl::bench::packetTraceSupported()) GTEST_SKIP() << "this CPU has no AVX-512";
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

INSTANTIATE_TEST_SUITE_P(Scenes, NativeRoofline, testing::Values("spheres_on_mirror", "mirror_wall", "half_sky"));

}  // namespace
