// Adaptive work: classification (rays only for pixels that reflect, the resolve only on 8x8 tiles
// holding one) must change what is dispatched, never the output; ray counts that follow
// roughness must give each pixel the count the documented rule says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "ssrcl/ssrcl.hpp"
#include "support/analytic_frame.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::Image;
using ssrcl::TraceSettings;

using Frame = ssrcl::test::AnalyticFrame;
using ssrcl::test::sharedTestDevice;

// The half-sky scene with roughness varying over the frame (a value per pixel that is never on a
// ray-count boundary of the rule under test), so sky, too-rough, mirror and glossy pixels all occur.
Frame halfSky(int width, int height) {
  Frame f = ssrcl::test::renderAnalyticFrame("half_sky", width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Mirror-like on the left tenth, then a ramp across the frame.
      const int m = (x * 7 + y * 3) % 97;
      f.g.roughness.at(x, y, 0) = x < width / 10 ? 0.01f : float(m + 0.5) / 97.0f;
    }
  return f;
}

struct Output {
  Image rgba, distance;
  ssrcl::StageTimes times;
};

Output run(ssrcl::Pipeline& p, const Frame& f, const TraceSettings& s) {
  ssrcl::test::runFrame(p, f, s);
  return {p.output("reflection"), p.output("distance"), p.stageTimes()};
}

Output run(const Frame& f, const TraceSettings& s) {
  ssrcl::Pipeline p(sharedTestDevice());
  return run(p, f, s);
}

bool isSurface(const Frame& f, int x, int y) {
  const float d = f.g.depth.at(x, y, 0);
  return std::isfinite(d) && d >= f.camera.nearPlane && d <= f.camera.farPlane;
}

std::vector<std::pair<std::string, TraceSettings>> variants() {
  std::vector<std::pair<std::string, TraceSettings>> v;
  for (const char* q : {"draft", "medium", "high"}) {
    TraceSettings s = ssrcl::qualityPreset(q);
    s.maxRoughness = 0.7f;  // a third of the ramp is too rough
    v.push_back({q, s});
  }
  v.push_back({"medium, rays follow roughness", v[1].second});
  v.back().second.fullRaysRoughness = 0.5f;
  v.push_back({"medium, linear tracer", v[1].second});
  v.back().second.tracer = ssrcl::Tracer::Linear;
  return v;
}

// Odd sizes: partial tiles at the right and bottom edges.
TEST(Classification, SameOutputAsDispatchingEveryPixel) {
  const Frame f = halfSky(333, 197);
  for (const auto& [name, settings] : variants()) {
    SCOPED_TRACE(name);
    TraceSettings every = settings;
    every.classifyWork = false;
    const Output classified = run(f, settings), all = run(f, every);
    EXPECT_EQ(classified.rgba.data, all.rgba.data);
    EXPECT_EQ(classified.distance.data, all.distance.data);
    EXPECT_EQ(classified.times.tracedRays, all.times.tracedRays);
    EXPECT_EQ(classified.times.tracedPixels, all.times.tracedPixels);
    EXPECT_EQ(all.times.resolvedTiles, 42 * 25);  // ceil(333 / 8) x ceil(197 / 8): every tile
    EXPECT_LT(classified.times.resolvedTiles, all.times.resolvedTiles);
  }
}

// Tiles listed are exactly those holding a surface pixel at or below the maximum roughness
// (counted here from the G-buffer), and every other pixel's output is zero.
TEST(Classification, ListsExactlyTheTilesThatReflect) {
  const Frame f = halfSky(333, 197);
  TraceSettings s = ssrcl::qualityPreset("medium");
  s.maxRoughness = 0.7f;
  const Output r = run(f, s);
  std::set<int> tiles;
  long long reflecting = 0, sky = 0, rough = 0;
  for (int y = 0; y < 197; ++y)
    for (int x = 0; x < 333; ++x) {
      const bool surface = isSurface(f, x, y), smooth = f.g.roughness.at(x, y, 0) <= s.maxRoughness;
      sky += !surface;
      rough += surface && !smooth;
      if (surface && smooth) {
        ++reflecting;
        tiles.insert((y / 8) * 42 + x / 8);
      } else {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(r.rgba.at(x, y, c), 0.0f) << x << "," << y;
        EXPECT_EQ(r.distance.at(x, y, 0), 0.0f) << x << "," << y;
      }
    }
  EXPECT_GT(sky, 333 * 197 / 3);  // the scene is as designed: a large sky, many too-rough pixels
  EXPECT_GT(rough, 333 * 197 / 10);
  EXPECT_EQ(r.times.tracedPixels, reflecting);
  EXPECT_EQ(r.times.resolvedTiles, static_cast<long long>(tiles.size()));
}

// A pipeline reused for another frame must not keep the last frame's reflections in tiles the new
// frame does not resolve.
TEST(Classification, ReusedPipelineClearsUnlistedTiles) {
  const Frame sky = halfSky(200, 120), full = ssrcl::test::renderAnalyticFrame("spheres_on_mirror", 200, 120);
  const TraceSettings s = ssrcl::qualityPreset("medium");
  ssrcl::Pipeline p(sharedTestDevice());
  const Output first = run(p, full, s);
  const Output second = run(p, sky, s);
  const Output fresh = run(sky, s);
  double firstAlpha = 0;
  for (size_t i = 3; i < first.rgba.data.size(); i += 4) firstAlpha += first.rgba.data[i];
  EXPECT_GT(firstAlpha, 1000.0);  // the first frame reflected in most places
  EXPECT_EQ(second.rgba.data, fresh.rgba.data);
  EXPECT_EQ(second.distance.data, fresh.distance.data);
}

// A frame too large for all its rays' records at once traces them in batches (TraceStage::plan);
// the next, smaller frame through the same pipeline and settings gets all of them in one again,
// as a fresh pipeline does (the batch had only shrunk from frame to frame; batches change the
// pass: each resolves its own rays).
TEST(Classification, ReusedPipelineSizesItsRayBatchesPerFrame) {
  Frame sky = halfSky(800, 800);  // 32 rays a pixel: 26 in a batch at this size
  std::fill(sky.g.depth.data.begin(), sky.g.depth.data.end(), INFINITY);  // all sky: nothing traced
  const Frame small = halfSky(200, 120);
  TraceSettings s = ssrcl::qualityPreset("medium");
  s.samplesPerPixel = 32;
  ssrcl::Pipeline p(sharedTestDevice());
  run(p, sky, s);
  const Output second = run(p, small, s), fresh = run(small, s);
  EXPECT_EQ(second.rgba.data, fresh.rgba.data);
}

// The rule: samplesPerPixel from fullRaysRoughness up, ceil(spp * r / full) below (at least 1),
// one ray at or below mirrorRoughness, none above maxRoughness or on the sky.
TEST(AdaptiveRays, CountsFollowRoughness) {
  const Frame f = halfSky(333, 197);
  for (float full : {0.25f, 0.5f, 1.0f}) {
    TraceSettings s = ssrcl::qualityPreset("medium");
    s.samplesPerPixel = 8;
    s.fullRaysRoughness = full;
    long long expected = 0, uniform = 0;
    for (int y = 0; y < 197; ++y)
      for (int x = 0; x < 333; ++x) {
        if (!isSurface(f, x, y)) continue;
        const double r = f.g.roughness.at(x, y, 0);
        const int n = r <= s.mirrorRoughness ? 1 : r >= full ? 8 : std::max(1, int(std::ceil(8 * r / full)));
        expected += n;
        uniform += r <= s.mirrorRoughness ? 1 : 8;
      }
    const Output r = run(f, s);
    EXPECT_EQ(r.times.tracedRays, expected) << "full rays from roughness " << full;
    EXPECT_LT(expected, uniform);
    s.fullRaysRoughness = 0.0f;
    EXPECT_EQ(run(f, s).times.tracedRays, uniform);
  }
}

}  // namespace
