// The bundled Cycles render (samples/blender/mirror): SSR on the mirror floor against Cycles'
// own path-traced answer, Glossy Direct + Glossy Indirect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"
#include "support/test_device.hpp"

namespace {

const std::string kSample = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/mirror/mirror.exr";
// The floor's specular colour in make_mirror_scene.py (metallic, base colour 0.8 grey): Cycles'
// glossy passes carry it, our pass is the radiance before it.
constexpr float kFloorSpecular = 0.8f;

ssrcl::Image loadRgb(const std::string& channels) {
  ssrcl::GBufferSource s;
  s.file = kSample;
  s.colorChannels = channels;
  s.readRoughness = false;
  return ssrcl::loadGBuffer(s).color;
}

TEST(BlenderSample, FloorReflectionsMatchCycles) {
  ssrcl::GBufferSource source;
  source.file = kSample;
  ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
  ssrcl::Image glossDir = loadRgb("ViewLayer.GlossDir.R,ViewLayer.GlossDir.G,ViewLayer.GlossDir.B");
  ssrcl::Image glossInd = loadRgb("ViewLayer.GlossInd.R,ViewLayer.GlossInd.G,ViewLayer.GlossInd.B");

  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(g);
  p.setCamera(ssrcl::loadCameraJson(std::string(SSRCL_SOURCE_DIR) + "/samples/blender/mirror/mirror.camera.json"));
  p.settings().edgeFade = 0.0f;
  p.commit();
  p.execute();
  const ssrcl::Image& refl = p.output("reflection");

  std::vector<double> errors;
  int floor = 0;
  for (int y = 0; y < g.depth.height; ++y)
    for (int x = 0; x < g.depth.width; ++x) {
      if (g.roughness.at(x, y, 0) != 0.0f || g.depth.at(x, y, 0) > 1e9f) continue;
      ++floor;
      if (refl.at(x, y, 3) < 1.0f) continue;
      for (int c = 0; c < 3; ++c) {
        double cycles = glossDir.at(x, y, c) + glossInd.at(x, y, c);
        double ours = kFloorSpecular * refl.at(x, y, c);
        // Relative error, with a floor so near-black pixels do not dominate.
        errors.push_back(std::abs(ours - cycles) / std::max(cycles, 0.02));
      }
    }
  ASSERT_GT(floor, 50000);
  // Most of the floor reflects the sky, which no screen-space method can find; what is found is
  // the reflections of the six objects, about a quarter of the floor.
  ASSERT_GT(errors.size() / 3, size_t(floor) / 5);
  std::sort(errors.begin(), errors.end());
  double median = errors[errors.size() / 2];
  double within25 = double(std::lower_bound(errors.begin(), errors.end(), 0.25) - errors.begin()) / errors.size();
  std::cout << "floor pixels " << floor << ", with a hit " << errors.size() / 3 << ", median relative error " << median
            << ", within 25%: " << within25 << "\n";
  // Cycles' 64-sample noise on the objects (seen directly in Combined and through the mirror in
  // the glossy passes, independently) is most of the remaining error: measured median 0.093 and
  // 90% within 25%. A hit on the wrong object or pixel row gives errors of 100% and more.
  EXPECT_LT(median, 0.13);
  EXPECT_GT(within25, 0.85);
}

}  // namespace

namespace {

// The glossy sample (three roughness stripes, sky black to glossy rays): every floor pixel
// against Cycles, see support/cycles_reference.hpp.
TEST(BlenderSample, GlossyFloorMatchesCycles) {
  const auto ref =
      ssrcl::test::loadCyclesReference(std::string(SSRCL_SOURCE_DIR) + "/samples/blender/glossy/glossy.exr");
  ASSERT_GT(ref.groups.front().second.size(), 70000u);
  ASSERT_EQ(ref.groups.size(), 4u);  // the floor and its three stripes
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(ref.gbuffer);
  p.setCamera(ref.camera);
  p.commit();
  auto run = [&](int spp) {
    p.settings().samplesPerPixel = spp;
    p.execute();
    return ssrcl::test::referenceError(ref, p.output("reflection"), ref.groups.front().second).rmse;
  };
  const double medium = run(4), more = run(16);
  std::cout << "glossy floor RMSE vs Cycles: medium " << medium << ", 16 rays " << more << "\n";
  // Measured 0.1135 and 0.0730 (reference mode: 0.0498; peak 5.76). Bounds 15% above: a wrong lobe
  // width, weight or hit test moves these by far more (before tangent-plane hits, 16 rays: 0.082).
  EXPECT_LT(medium, 0.13);
  EXPECT_LT(more, 0.084);
  EXPECT_LT(more, 0.8 * medium);  // more rays, less error: the estimator converges
}

}  // namespace
