// SSR on analytic mirror scenes against exact ray-traced reflections, plus checks of the truth
// generator itself (tests/support/analytic_scene.*).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/pipeline.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::test;
using glm::dvec3;

// Colour tolerance (max abs error per channel). The pattern's gradient is at most
// 0.4 * 2 pi / period ~ 2.5 per world unit (period 1, base <= 1); a pixel spans ~0.02 world units
// on a surface seen head-on 10 units away at 480x270, so one pixel of hit error costs up to 0.05
// there, and a hit two pixels off or on another surface costs more.
constexpr double kColorTol = 0.05;
// Relative tolerance on the distance channel ("a few %").
constexpr double kDistanceTol = 0.05;
// Where the surface is seen at a grazing angle, or the hit is within a pixel of a silhouette,
// one pixel of screen-space error (inherent to SSR: it resolves hits per depth-buffer pixel)
// moves colour or distance by more than that; the truth measures how much (colorSpread,
// distanceSpread) and the allowance adds it. Resolvable hits (spreads within the tolerances, no
// silhouette) are also held to the tolerances alone.
double colorAllowance(const MirrorSample& s) { return kColorTol + s.colorSpread; }
double distanceAllowance(const MirrorSample& s) { return kDistanceTol + s.distanceSpread; }
bool resolvable(const MirrorSample& s) {
  return !s.nearEdge && s.colorSpread <= kColorTol && s.distanceSpread <= kDistanceTol;
}

struct Case {
  const char* scene;
  int width, height;
};
// An odd, non-power-of-two size catches off-by-one and mip-rounding errors.
const Case kCases[] = {
    {"spheres_on_mirror", 480, 270},
    {"spheres_on_mirror", 333, 197},
    {"mirror_wall", 480, 270},
    {"mirror_wall", 333, 197},
};

std::string caseName(const Case& c) {
  return std::string(c.scene) + "_" + std::to_string(c.width) + "x" + std::to_string(c.height);
}
// Stable test names in ctest (the default printer dumps the struct's bytes, pointer included).
void PrintTo(const Case& c, std::ostream* os) { *os << caseName(c); }

struct Rendered {
  Scene scene;
  ssrcl::Camera camera;
  AnalyticGBuffer g;
  MirrorTruth truth;
};

Rendered render(const Case& c) {
  Rendered r;
  r.scene = makeScene(c.scene);
  r.camera = makeCamera(r.scene.view, c.width, c.height);
  r.g = renderGBuffer(r.scene, r.camera);
  r.truth = exactMirrorReflection(r.scene, r.camera, r.g);
  return r;
}

double maxAbsDiff(const dvec3& expected, const ssrcl::Image& img, int x, int y) {
  double d = 0;
  for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(double(img.at(x, y, c)) - expected[c]));
  return d;
}

// The G-buffer pixel under a projected hit.
void pixelOf(const MirrorSample& s, int& px, int& py) {
  px = int(std::floor(s.screen.x));
  py = int(std::floor(s.screen.y));
}

double fraction(std::size_t n, std::size_t d) { return d ? double(n) / double(d) : 1.0; }

// ---------------------------------------------------------------------------------------------
// The generator, independently of SSR.

class GeneratorTest : public ::testing::TestWithParam<Case> {};

TEST_P(GeneratorTest, ReflectionLawHolds) {
  const Rendered r = render(GetParam());
  for (int y = 0; y < r.g.height; ++y)
    for (int x = 0; x < r.g.width; ++x) {
      const MirrorSample& s = r.truth.at(x, y);
      const Hit& h = r.g.hit(x, y);
      ASSERT_EQ(bool(h), s.cls != ReflectionClass::NoSurface) << x << "," << y;
      if (!h) continue;
      const dvec3 v = primaryRay(r.camera, x + 0.5, y + 0.5).direction;
      const dvec3 d = s.reflected.direction;
      ASSERT_NEAR(glm::length(d), 1.0, 1e-12);
      ASSERT_NEAR(glm::length(h.normal), 1.0, 1e-12);
      // Angle in = angle out, and in, out and the normal are coplanar (d - v parallel to n).
      ASSERT_NEAR(glm::dot(d, h.normal), -glm::dot(v, h.normal), 1e-12) << x << "," << y;
      ASSERT_LT(glm::length(glm::cross(d - v, h.normal)), 1e-12) << x << "," << y;
      ASSERT_EQ(s.reflected.origin, h.position);
      if (s.hit) {
        ASSERT_GT(s.hit.t, 0.0);
        ASSERT_NEAR(glm::length(s.hit.position - s.reflected.origin), s.hit.t, 1e-9 * (1 + s.hit.t));
      }
    }
}

TEST_P(GeneratorTest, GBufferMatchesPrimaryHits) {
  const Rendered r = render(GetParam());
  std::size_t sky = 0;
  for (int y = 0; y < r.g.height; ++y)
    for (int x = 0; x < r.g.width; ++x) {
      const Hit& h = r.g.hit(x, y);
      if (!h) {
        ++sky;
        ASSERT_EQ(r.g.depth.at(x, y, 0), float(kSkyDepth));
        continue;
      }
      // The hit is where the pixel centre projects and its depth is what is stored.
      const dvec3 p = projectToScreen(r.camera, h.position);
      ASSERT_NEAR(p.x, x + 0.5, 1e-6);
      ASSERT_NEAR(p.y, y + 0.5, 1e-6);
      ASSERT_NEAR(r.g.depth.at(x, y, 0), p.z, 1e-6 * p.z);
      ASSERT_GT(p.z, r.camera.nearPlane);
    }
  // The presets are meant to show some sky.
  EXPECT_GT(sky, r.g.hits.size() / 50);
}

TEST_P(GeneratorTest, EveryClassIsWellRepresented) {
  const Rendered r = render(GetParam());
  std::size_t surface = r.g.hits.size() - r.truth.count(ReflectionClass::NoSurface);
  std::ostringstream line;
  line << caseName(GetParam()) << " surface " << surface;
  for (auto c :
       {ReflectionClass::Visible, ReflectionClass::OffScreen, ReflectionClass::Occluded, ReflectionClass::Sky}) {
    line << " " << className(c) << " " << r.truth.count(c);
    // At least 1% of the surface pixels each, so every branch of the SSR is exercised.
    EXPECT_GT(r.truth.count(c), surface / 100) << className(c);
  }
  std::cout << line.str() << "\n";
}

// An ideal screen-space tracer that returns the nearest pixel of the exact hit stays within the
// allowances: they are reachable, and the G-buffer agrees with the truth where it should.
TEST_P(GeneratorTest, VisibleHitsAgreeWithGBuffer) {
  const Rendered r = render(GetParam());
  std::size_t visible = 0, colorOk = 0, depthOk = 0, strict = 0, resolvableCount = 0;
  for (const MirrorSample& s : r.truth.samples) {
    if (s.cls == ReflectionClass::Occluded) {
      // Something lies strictly in front of an occluded hit.
      const Hit seen = intersect(r.scene, primaryRay(r.camera, s.screen.x, s.screen.y));
      ASSERT_TRUE(seen);
      ASSERT_LT(planarDepth(r.camera, seen.position), s.screen.z * (1 - 1e-9));
    }
    if (s.cls != ReflectionClass::Visible) continue;
    ++visible;
    int px, py;
    pixelOf(s, px, py);
    ASSERT_GE(px, 0);
    ASSERT_LT(px, r.g.width);
    ASSERT_GE(py, 0);
    ASSERT_LT(py, r.g.height);
    const double err = maxAbsDiff(s.color, r.g.color, px, py);
    colorOk += err <= colorAllowance(s);
    depthOk += s.nearEdge || std::abs(r.g.depth.at(px, py, 0) - s.screen.z) <= 0.02 * s.screen.z;
    resolvableCount += resolvable(s);
    strict += err <= kColorTol;
  }
  std::cout << caseName(GetParam()) << " nearest-pixel tracer: colour within allowance " << fraction(colorOk, visible)
            << ", within " << kColorTol << " " << fraction(strict, visible) << "; depth " << fraction(depthOk, visible)
            << "; resolvable " << fraction(resolvableCount, visible) << " of " << visible << " visible\n";
  // The spreads come from rays 1 px away and the nearest pixel centre is at most 0.71 px away, so
  // nearly all pass; a few depth misses sit at silhouettes that the 8 rays straddle.
  EXPECT_GE(fraction(colorOk, visible), 0.999);
  EXPECT_GE(fraction(depthOk, visible), 0.999);
}

INSTANTIATE_TEST_SUITE_P(Analytic, GeneratorTest, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return caseName(info.param); });

// Camera straight above an infinite mirror floor (fov 90, square, odd size so the middle row is
// at NDC y = 0): values below follow from the virtual-camera construction, not from reflect().
struct TopDown {
  Scene scene;
  ssrcl::Camera camera;
  static constexpr int kSize = 101;
  static constexpr double kHeight = 10.0;
  TopDown() {
    scene.primitives = {plane("floor", dvec3(0.0), dvec3(0, 1, 0), Material{dvec3(0.5)})};
    ViewParams v;
    v.eye = dvec3(0, kHeight, 0);
    v.target = dvec3(0.0);
    v.up = dvec3(0, 0, -1);  // screen right = +X, screen up = -Z
    v.fovYDegrees = 90.0;
    camera = makeCamera(v, kSize, kSize);
  }
};

TEST(GeneratorHandCase, FloorPixelReflectsIntoSphereUnderside) {
  TopDown td;
  // Pixel (60, 50) sees the floor at x = h * NDC x = 10 * 20/101, z = 0.
  const int px = 60, py = 50;
  const dvec3 p(TopDown::kHeight * (2.0 * px + 1.0 - TopDown::kSize) / TopDown::kSize, 0, 0);
  // The reflected ray runs from the eye's mirror image E' = (0, -h, 0) through p. Put a unit
  // sphere's centre on it, |E'p| / 2 beyond p.
  const dvec3 virtualEye(0, -TopDown::kHeight, 0);
  const dvec3 centre = p + 0.5 * (p - virtualEye);
  td.scene.primitives.push_back(sphere("ball", centre, 1.0, Material{dvec3(0.9, 0.2, 0.1)}));
  const AnalyticGBuffer g = renderGBuffer(td.scene, td.camera);
  ASSERT_EQ(g.hit(px, py).primitive, 0);
  EXPECT_NEAR(glm::length(g.hit(px, py).position - p), 0.0, 1e-12);
  EXPECT_FLOAT_EQ(g.depth.at(px, py, 0), float(TopDown::kHeight));

  const MirrorTruth t = exactMirrorReflection(td.scene, td.camera, g);
  const MirrorSample& s = t.at(px, py);
  const dvec3 dir = glm::normalize(p - virtualEye);
  const double dist = 0.5 * glm::length(p - virtualEye) - 1.0;  // |p - centre| minus the radius
  EXPECT_NEAR(glm::length(s.reflected.direction - dir), 0.0, 1e-12);
  ASSERT_EQ(s.hit.primitive, 1);
  EXPECT_NEAR(s.hit.t, dist, 1e-9);
  EXPECT_NEAR(glm::length(s.hit.position - (centre - dir)), 0.0, 1e-9);
  // The hit (2.776, 4.019, 0) projects on screen but its normal (-dir) points down, away from
  // the camera above: hidden.
  EXPECT_EQ(s.cls, ReflectionClass::Occluded);
  // Numbers for the record: p = (1.980198, 0, 0), |E'p| = sqrt(p.x^2 + 100) = 10.194174.
  EXPECT_NEAR(p.x, 1.98019802, 1e-8);
  EXPECT_NEAR(dist, 4.097087, 1e-6);
}

TEST(GeneratorHandCase, SphereEquatorReflectsOntoVisibleFloor) {
  TopDown td;
  td.scene.primitives.push_back(sphere("ball", dvec3(3, 2, 0), 1.0, Material{dvec3(0.9, 0.2, 0.1)}));
  // The eye (0, 10, 0) sees the equator point q = (2, 2, 0) (normal -X) along (1, -4, 0)/sqrt 17;
  // the mirror flips the x component: (-1, -4, 0)/sqrt 17, reaching y = 0 at (1.5, 0, 0) after
  // sqrt(17)/2. The eye sees that floor point (the sphere is > 1 away from the line of sight).
  const dvec3 q(2, 2, 0);
  const Ray view = primaryRay(td.camera, projectToScreen(td.camera, q).x, projectToScreen(td.camera, q).y);
  const Hit surface = intersect(td.scene, view);
  ASSERT_EQ(surface.primitive, 1);
  EXPECT_NEAR(glm::length(surface.position - q), 0.0, 1e-9);
  const MirrorSample s = reflectAt(td.scene, td.camera, surface, view.direction);
  EXPECT_NEAR(glm::length(s.reflected.direction - dvec3(-1, -4, 0) / std::sqrt(17.0)), 0.0, 1e-9);
  ASSERT_EQ(s.hit.primitive, 0);
  EXPECT_NEAR(s.hit.t, std::sqrt(17.0) / 2.0, 1e-9);
  EXPECT_NEAR(glm::length(s.hit.position - dvec3(1.5, 0, 0)), 0.0, 1e-9);
  EXPECT_EQ(s.cls, ReflectionClass::Visible);
  // (1.5, 0, 0) at depth 10 and fov 90: NDC (0.15, 0) -> pixel (0.575 W, 0.5 H).
  EXPECT_NEAR(s.screen.x, 0.575 * TopDown::kSize, 1e-9);
  EXPECT_NEAR(s.screen.y, 0.5 * TopDown::kSize, 1e-9);
  EXPECT_NEAR(s.screen.z, 10.0, 1e-9);
  EXPECT_EQ(s.color, colorAt(td.scene, s.hit));
}

TEST(GeneratorHandCase, UpwardReflectionOfFloorIsSky) {
  TopDown td;
  const AnalyticGBuffer g = renderGBuffer(td.scene, td.camera);
  const MirrorTruth t = exactMirrorReflection(td.scene, td.camera, g);
  EXPECT_EQ(t.count(ReflectionClass::Sky), g.hits.size());
  EXPECT_EQ(t.at(50, 50).color, td.scene.skyColor);
}

// ---------------------------------------------------------------------------------------------
// The SSR pipeline against the truth.

class MirrorSsrTest : public ::testing::TestWithParam<Case> {};

TEST_P(MirrorSsrTest, MatchesExactReflections) {
  const Case& c = GetParam();
  const Rendered r = render(c);

  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(r.g);
  p.setCamera(r.camera);
  p.settings().edgeFade = 0;  // the truth has no fade: a visible hit at the border is full strength
  p.commit();
  p.execute();
  const ssrcl::Image& refl = p.output("reflection");
  const ssrcl::Image& dist = p.output("distance");
  ASSERT_EQ(refl.width, c.width);
  ASSERT_EQ(refl.height, c.height);
  ASSERT_EQ(refl.channels, 4);
  ASSERT_EQ(dist.width, c.width);
  ASSERT_EQ(dist.height, c.height);
  ASSERT_EQ(dist.channels, 1);

  std::size_t visible = 0, colorOk = 0, distOk = 0, strictOk = 0, resolvableCount = 0, resolvableOk = 0;
  std::size_t missTotal = 0, missOk = 0, occluded = 0, occludedHit = 0;
  std::vector<std::string> badVisible, badMiss;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const MirrorSample& s = r.truth.at(x, y);
      const float a = refl.at(x, y, 3), d = dist.at(x, y, 0);
      for (int ch = 0; ch < 4; ++ch) ASSERT_TRUE(std::isfinite(refl.at(x, y, ch))) << x << "," << y;
      ASSERT_TRUE(std::isfinite(d)) << x << "," << y;
      ASSERT_GE(a, 0.0f) << x << "," << y;
      ASSERT_LE(a, 1.0f) << x << "," << y;
      ASSERT_GE(d, 0.0f) << x << "," << y;
      switch (s.cls) {
        case ReflectionClass::NoSurface:
          // Sky pixels get no ray at all.
          for (int ch = 0; ch < 4; ++ch) ASSERT_EQ(refl.at(x, y, ch), 0.0f) << x << "," << y;
          ASSERT_EQ(d, 0.0f) << x << "," << y;
          break;
        case ReflectionClass::Visible: {
          ++visible;
          // RGB is premultiplied: a full-confidence hit must carry the exact colour.
          const double err = maxAbsDiff(s.color, refl, x, y), relD = std::abs(d - s.hit.t) / s.hit.t;
          const bool okC = err <= colorAllowance(s), okD = relD <= distanceAllowance(s);
          const bool strict = err <= kColorTol && relD <= kDistanceTol;
          colorOk += okC;
          distOk += okD;
          strictOk += strict;
          resolvableCount += resolvable(s);
          resolvableOk += resolvable(s) && strict;
          if (!(okC && okD)) {
            std::ostringstream o;
            o << "(" << x << "," << y << ") on " << r.scene.primitives[std::size_t(r.g.hit(x, y).primitive)].name
              << " exp rgb " << s.color.r << " " << s.color.g << " " << s.color.b << " dist " << s.hit.t << " ("
              << r.scene.primitives[std::size_t(s.hit.primitive)].name << " at px " << s.screen.x << "," << s.screen.y
              << (s.nearEdge ? ", near edge" : "") << ", allow " << colorAllowance(s) << "/" << distanceAllowance(s)
              << ") got rgba " << refl.at(x, y, 0) << " " << refl.at(x, y, 1) << " " << refl.at(x, y, 2) << " " << a
              << " dist " << d;
            badVisible.push_back(o.str());
          }
          break;
        }
        case ReflectionClass::Sky:
        case ReflectionClass::OffScreen:
          ++missTotal;
          if (a == 0.0f) {
            ++missOk;
          } else {
            std::ostringstream o;
            o << "(" << x << "," << y << ") " << className(s.cls) << " on "
              << r.scene.primitives[std::size_t(r.g.hit(x, y).primitive)].name << " got rgba " << refl.at(x, y, 0)
              << " " << refl.at(x, y, 1) << " " << refl.at(x, y, 2) << " " << a << " dist " << d;
            badMiss.push_back(o.str());
          }
          break;
        case ReflectionClass::Occluded:
          ++occluded;
          occludedHit += a > 0.0f;
          break;
      }
    }

  const double colorRate = fraction(colorOk, visible), distRate = fraction(distOk, visible);
  const double strictRate = fraction(strictOk, visible), resolvableRate = fraction(resolvableOk, resolvableCount);
  const double missRate = fraction(missOk, missTotal), occludedHitRate = fraction(occludedHit, occluded);
  std::cout << caseName(c) << ": visible " << visible << " colour match " << colorRate << " distance match " << distRate
            << " (strict " << strictRate << ", on " << resolvableCount << " resolvable " << resolvableRate
            << "); sky/offscreen " << missTotal << " reported miss " << missRate << "; occluded " << occluded
            << " marked hit " << occludedHitRate << "\n";
  RecordProperty("visible_color_match", std::to_string(colorRate));
  RecordProperty("visible_distance_match", std::to_string(distRate));
  RecordProperty("visible_strict_match", std::to_string(strictRate));
  RecordProperty("resolvable_strict_match", std::to_string(resolvableRate));
  RecordProperty("miss_reported", std::to_string(missRate));
  RecordProperty("occluded_marked_hit", std::to_string(occludedHitRate));

  const auto dump = [](const std::vector<std::string>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size() && i < 25; ++i) out += "  " + v[i] + "\n";
    return out + "  (" + std::to_string(v.size()) + " in all)\n";
  };
  // Visible: within the per-pixel allowance, and on the resolvable ones (where one pixel of
  // error costs less than the fixed tolerances) within those. The residue is hits the march steps
  // over or misses by more than a pixel. Measured (PoCL, issue 17) over the four cases: colour
  // 0.9938-0.9959, distance 0.9932-0.9965, resolvable 0.9948-0.9973. Floor 0.99: the margin is
  // for hit decisions at pixel edges that another platform's float rounding flips (tens of pixels
  // of 10000-40000); twice the surface thickness falls below it (colour 0.970 on mirror_wall).
  EXPECT_GE(colorRate, 0.99) << dump(badVisible);
  EXPECT_GE(distRate, 0.99) << dump(badVisible);
  EXPECT_GE(resolvableRate, 0.99) << dump(badVisible);
  // Sky/OffScreen: the exact ray hits nothing on screen, but a screen-space march may pass within
  // thickness behind some surface near silhouettes and screen borders (e.g. a ray leaving through
  // the bottom edge just above the floor). Measured 0.9943-0.9959; floor 0.99 as above (twice the
  // thickness: 0.978).
  EXPECT_GE(missRate, 0.99) << dump(badMiss);
  // Occluded: not asserted. The exact hit is hidden; the ray passes behind the occluder and a
  // screen-space tracer reports the occluder whenever it is within thickness there: expected SSR
  // behaviour, only reported.
}

// Edge fade (a non-default value; every other truth test sets it to 0): a visible hit's A is its
// exact screen point's distance to the nearest border over edgeFade * the smaller side, clamped to
// [0, 1]. The hit SSR finds lies within a pixel or two of the exact one, which moves A by up to
// 2 / (edgeFade * side); hits near silhouettes get the same 3% residue as the colour assertions.
TEST_P(MirrorSsrTest, EdgeFadeFollowsTheHitsDistanceToTheBorder) {
  const Case& c = GetParam();
  const Rendered r = render(c);
  const float fade = 0.2f;  // wide enough that a large share of the hits lies inside the fade band
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(r.g);
  p.setCamera(r.camera);
  p.settings().edgeFade = fade;
  p.commit();
  p.execute();
  const ssrcl::Image& refl = p.output("reflection");
  const double band = fade * std::min(c.width, c.height), tol = 2.0 / band;
  std::size_t checked = 0, ok = 0, faded = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const MirrorSample& s = r.truth.at(x, y);
      if (s.cls != ReflectionClass::Visible || !resolvable(s)) continue;
      const double border = std::min(std::min(s.screen.x, c.width - s.screen.x), std::min(s.screen.y, c.height - s.screen.y));
      const double expected = std::clamp(border / band, 0.0, 1.0);
      ++checked;
      faded += expected < 1.0 - tol;
      ok += std::abs(refl.at(x, y, 3) - expected) <= tol;
    }
  std::cout << caseName(c) << ": edge fade " << fade << ": " << checked << " resolvable hits, " << faded
            << " inside the band, A within " << tol << " of truth for " << fraction(ok, checked) << "\n";
  ASSERT_GT(faded, checked / 10);  // the band must matter for the check to mean anything
  EXPECT_GE(fraction(ok, checked), 0.97);
}

INSTANTIATE_TEST_SUITE_P(Analytic, MirrorSsrTest, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return caseName(info.param); });

}  // namespace
