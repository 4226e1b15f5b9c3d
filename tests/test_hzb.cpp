// HZB min pyramid against a CPU reference that takes the min over each coarse texel's whole
// pixel block directly (not level by level), so a dropped edge row or column anywhere shows up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <random>

#include "ssrcl/ssrcl.hpp"
#include "support/simple_camera.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::Image;

struct Inputs {
  Image color, depth, normal;
};

// Random depths in [1, 50], with some sky (1e10) and a few non-finite values, both of which
// must become "no surface" (FLT_MAX) in the pyramid.
Inputs randomInputs(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> depth(1.0f, 50.0f);
  std::uniform_int_distribution<int> kind(0, 19);
  Inputs in{Image(w, h, 3), Image(w, h, 1), Image(w, h, 3)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int k = kind(rng);
      in.depth.at(x, y, 0) = k == 0 ? 1e10f : k == 1 ? std::numeric_limits<float>::quiet_NaN() : depth(rng);
      in.normal.at(x, y, 2) = 1.0f;
    }
  return in;
}

float expectedDepth(float d) { return (std::isfinite(d) && d >= 0.1f && d <= 100.0f) ? d : FLT_MAX; }

void checkPyramid(int w, int h) {
  SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
  Inputs in = randomInputs(w, h, unsigned(w * 7919 + h));
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setImage("color", in.color);
  p.setImage("depth", in.depth);
  p.setImage("normal", in.normal);
  p.setCamera(ssrcl::test::perspectiveCamera(w, h));
  // Every pixel above the roughness cutoff: only the pyramid is built, no ray is traced.
  p.settings().constantRoughness = 1.0f;
  p.settings().maxRoughness = 0.5f;
  p.commit();
  p.execute();
  EXPECT_EQ(p.stageTimes().tracedRays, 0);
  std::vector<Image> mips = p.readHzb();

  // Down to 1x1, each level ceil(previous / 2).
  int levels = 1;
  for (int lw = w, lh = h; lw > 1 || lh > 1; lw = (lw + 1) / 2, lh = (lh + 1) / 2) ++levels;
  ASSERT_EQ(int(mips.size()), levels);
  EXPECT_EQ(mips.back().width, 1);
  EXPECT_EQ(mips.back().height, 1);

  for (int l = 0; l < levels; ++l) {
    const Image& m = mips[l];
    const int block = 1 << l;
    ASSERT_EQ(m.width, (w + block - 1) / block) << "level " << l;
    ASSERT_EQ(m.height, (h + block - 1) / block) << "level " << l;
    int wrong = 0;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        float ref = FLT_MAX;
        for (int py = y * block; py < std::min(h, (y + 1) * block); ++py)
          for (int px = x * block; px < std::min(w, (x + 1) * block); ++px)
            ref = std::min(ref, expectedDepth(in.depth.at(px, py, 0)));
        if (m.at(x, y, 0) != ref && ++wrong < 5)
          ADD_FAILURE() << "level " << l << " texel " << x << "," << y << ": " << m.at(x, y, 0) << " != " << ref;
      }
    EXPECT_EQ(wrong, 0) << "level " << l;
  }
}

TEST(Hzb, OnePixel) { checkPyramid(1, 1); }
TEST(Hzb, OddTiny) { checkPyramid(3, 5); }
TEST(Hzb, Row) { checkPyramid(17, 1); }
TEST(Hzb, FullHd) { checkPyramid(1920, 1080); }
TEST(Hzb, WideOdd) { checkPyramid(4097, 3); }

}  // namespace
