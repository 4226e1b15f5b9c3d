// The OpenCL mirror pass against the native C++ implementation of the same rays
// (bench/native_mirror_trace, the roofline of `ssrcl bench --roofline`): written separately from
// the kernels, same float arithmetic, so every pixel's hit must agree but for float ties.
#include <gtest/gtest.h>

#include "native_mirror_trace.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/test_device.hpp"

namespace {

class NativeRoofline : public testing::TestWithParam<const char*> {};

TEST_P(NativeRoofline, HitsAgreeWithOpenCl) {
  const ssrcl::test::Scene scene = ssrcl::test::makeScene(GetParam());
  const ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, 320, 180);
  const ssrcl::GBuffer g = ssrcl::test::renderGBuffer(scene, camera);
  const ssrcl::TraceSettings settings = ssrcl::bench::nativeMirrorSettings();

  ssrcl::Pipeline p(ssrcl::test::testDevice());
  p.setGBuffer(g);
  p.setCamera(camera);
  p.settings() = settings;
  p.commit();
  p.execute();
  ssrcl::bench::NativeMirrorTrace native(g, camera, settings);
  native.run(2);

  EXPECT_EQ(native.rays(), p.stageTimes().tracedRays);
  const auto hits = ssrcl::bench::compareHitDistances(native.distance(), p.output("distance").data);
  ASSERT_GT(hits.hitPixels, 1000);  // the scene reflects something: the comparison means something
  EXPECT_LE(hits.disagreeing, hits.hitPixels / 1000) << hits.disagreeing << " of " << hits.hitPixels;
}

INSTANTIATE_TEST_SUITE_P(Scenes, NativeRoofline, testing::Values("spheres_on_mirror", "mirror_wall", "half_sky"));

}  // namespace
