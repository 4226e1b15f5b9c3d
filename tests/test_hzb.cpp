// HZB min pyramid against a CPU reference in double precision: level 0 is the nearest depth of
// each pixel's surface (the plane through its point with its normal) over the pixel's square,
// and every coarser texel the min over its whole pixel block, taken directly (not level by
// level) so a dropped edge row or column anywhere shows up. The setup and HZB stages run on their
// own, through the library's internals (the pipeline keeps its pyramid to itself).
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <glm/glm.hpp>
#include <random>

#include "pipeline/color_pyramid_stage.hpp"
#include "pipeline/hzb_stage.hpp"
#include "pipeline/setup_stage.hpp"
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

// Nearest depth of the pixel's tangent plane over its square, corners clamped to half the centre
// depth (as setup documents), FLT_MAX for no surface.
std::vector<double> footprintMin(const Inputs& in, const ssrcl::Camera& cam) {
  const int w = cam.width, h = cam.height;
  const glm::dmat4 invProj = glm::inverse(cam.projection);
  const glm::dvec3 n = glm::normalize(glm::dmat3(cam.view) * glm::dvec3(0, 0, 1));
  auto line = [&](double sx, double sy, glm::dvec3& a, glm::dvec3& b) {
    glm::dvec2 ndc(2 * sx / w - 1, 1 - 2 * sy / h);
    glm::dvec4 ha = invProj * glm::dvec4(ndc, -1, 1), hb = invProj * glm::dvec4(ndc, 0, 1);
    a = glm::dvec3(ha) / ha.w;
    b = glm::dvec3(hb) / hb.w;
  };
  std::vector<double> out(size_t(w) * h, FLT_MAX);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double d = in.depth.at(x, y, 0);
      if (!(std::isfinite(d) && d >= 0.1 && d <= 100.0)) continue;
      glm::dvec3 a, b;
      line(x + 0.5, y + 0.5, a, b);
      const glm::dvec3 p = a + (b - a) * ((-d - a.z) / (b.z - a.z));
      double nearest = d;
      for (int c = 0; c < 4; ++c) {
        line(x + (c & 1), y + (c >> 1), a, b);
        const double lambda = glm::dot(p - a, n) / glm::dot(b - a, n);
        if (lambda >= 0) nearest = std::min(nearest, std::max(-(a.z + lambda * (b.z - a.z)), 0.5 * d));
      }
      out[size_t(y) * w + x] = nearest;
    }
  return out;
}

// Setup and HZB as the pipeline runs them; every level read back.
std::vector<Image> buildHzb(const ssrcl::Device& device, const Inputs& in, const ssrcl::Camera& camera) {
  using namespace ssrcl::detail;
  ssrcl::Device::Impl& d = DeviceAccess::impl(device);
  ssrcl::TraceSettings s;
  s.constantRoughness = 1.0f;
  const FrameShape frame(camera.width, camera.height);
  SetupStage setup;
  HzbStage hzb;
  ColorPyramidStage colors;
  setup.configure(d);
  hzb.configure(d);
  colors.configure(d, s);
  DeviceBuffers buffers;
  FrameResources resources;
  resources.beginPlan();
  setup.plan(resources, buffers, frame, 3, false, false);
  hzb.plan(resources, buffers, frame);
  colors.plan(resources, buffers, frame);
  buffers.allocate(d, "the test frame");
  setup.bind(resources);
  hzb.bind(d.queue, resources);
  StageEvents events;
  setup.enqueue(d.queue, {in.color.data.data(), in.depth.data.data(), in.normal.data.data(), nullptr},
                SetupStage::params(frameConstants(frame, camera, s), s, 3), events);
  hzb.enqueue(d.queue, events);
  const StageAccess readBack{"the test", {Role::DepthPyramid}, {}};
  std::vector<Image> mips;
  for (const HzbLevel& l : frame.levels) {
    mips.emplace_back(l.width, l.height, 1);
    d.queue.enqueueReadBuffer(resources.read(readBack, Role::DepthPyramid), CL_TRUE, l.offset * sizeof(float), mips.back().data.size() * sizeof(float),
                              mips.back().data.data());
  }
  return mips;
}

void checkPyramid(int w, int h) {
  SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
  Inputs in = randomInputs(w, h, unsigned(w * 7919 + h));
  const ssrcl::Camera camera = ssrcl::test::perspectiveCamera(w, h);
  std::vector<Image> mips = buildHzb(ssrcl::test::testDevice(), in, camera);
  const std::vector<double> level0 = footprintMin(in, camera);

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
        double ref = FLT_MAX;
        for (int py = y * block; py < std::min(h, (y + 1) * block); ++py)
          for (int px = x * block; px < std::min(w, (x + 1) * block); ++px)
            ref = std::min(ref, level0[size_t(py) * w + px]);
        // Float arithmetic in the kernel: a few ulps of the depth.
        const double tolerance = ref == FLT_MAX ? 0.0 : 1e-5 * ref;
        if (!(std::abs(m.at(x, y, 0) - ref) <= tolerance) && ++wrong < 5)
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
