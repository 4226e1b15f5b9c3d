// Numerical extremes (issue 6): every corner case a production frame can hold, each with an
// asserted outcome, and on every one of them the output is finite with A in [0, 1] for the
// mirror path and every quality preset (reference with few rays, to keep the time down).
//
//   * Hostile G-buffer values (roughness, normals, depth, colour): exact equivalences, e.g. a
//     NaN depth gives bit for bit the output of the sky, a colour of 1e30 that of 1e20.
//   * Geometric extremes (rays toward the camera, parallel to the image plane, reflections of
//     points behind the camera, near/far ratios, reversed-Z and infinite-far projections,
//     orthographic and off-centre cameras, odd and huge resolutions): against the exact
//     reflections of analytic scenes, each hit on the right pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/glm.hpp>
#include <iostream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "pipeline/device_impl.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl;
using namespace ssrcl::test;
using glm::dvec3;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kPi = 3.14159265358979323846;

Device& device() {
  static Device d = testDevice();
  return d;
}

struct Frame {
  Camera camera;
  Image color, depth, normal, roughness;
};

Frame frameOf(const AnalyticGBuffer& g, const Camera& camera) {
  return {camera, g.color, g.depth, g.normal, g.roughness};
}

struct Result {
  Image rgba, distance;
  StageTimes times;
};

Result run(const Frame& f, const TraceSettings& s) {
  Pipeline p(device());
  p.setImage("color", f.color);
  p.setImage("depth", f.depth);
  p.setImage("normal", f.normal);
  if (!f.roughness.empty()) p.setImage("roughness", f.roughness);
  p.setCamera(f.camera);
  p.settings() = s;
  p.commit();
  p.execute();
  return {p.output("reflection"), p.output("distance"), p.stageTimes()};
}

// The mirror path (every pixel one exact mirror ray) and the quality presets, reference with 4
// rays instead of 256.
std::vector<std::pair<std::string, TraceSettings>> variants() {
  TraceSettings mirror = qualityPreset("medium");
  mirror.mirrorRoughness = 1.0f;
  TraceSettings mirrorDda = mirror;
  mirrorDda.tracer = Tracer::DDA;
  TraceSettings reference = qualityPreset("reference");
  reference.samplesPerPixel = 4;
  TraceSettings high = qualityPreset("high");
  high.samplesPerPixel = 4;
  return {{"mirror", mirror},
          {"mirror-dda", mirrorDda},
          {"draft", qualityPreset("draft")},
          {"medium", qualityPreset("medium")},
          {"high(4 spp)", high},
          {"reference(4 spp)", reference}};
}

// Finite everywhere, A in [0, 1], RGB >= 0 (premultiplied radiance), distance >= 0, and nothing
// where A is 0. Returns the number of bad pixels (the first few are reported).
int expectSane(const Result& r, const std::string& label) {
  int bad = 0;
  for (int y = 0; y < r.rgba.height; ++y)
    for (int x = 0; x < r.rgba.width; ++x) {
      const float a = r.rgba.at(x, y, 3), d = r.distance.at(x, y, 0);
      bool ok = a >= 0.0f && a <= 1.0f && std::isfinite(d) && d >= 0.0f;
      for (int c = 0; c < 3; ++c) ok = ok && std::isfinite(r.rgba.at(x, y, c)) && r.rgba.at(x, y, c) >= 0.0f;
      // Premultiplied: nothing where A is 0. (The optional filter can leave a few 1e-26 there, where
      // its weights underflow for A but not for RGB; negligible, so checked to 1e-12.)
      if (a == 0.0f)
        for (int c = 0; c < 3; ++c) ok = ok && r.rgba.at(x, y, c) <= 1e-12f;
      if (!ok && ++bad <= 5)
        ADD_FAILURE() << label << ": pixel " << x << "," << y << " rgba " << r.rgba.at(x, y, 0) << " "
                      << r.rgba.at(x, y, 1) << " " << r.rgba.at(x, y, 2) << " " << a << " distance " << d;
    }
  return bad;
}

bool sameBits(const Image& a, const Image& b) {
  return a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

// Runs both frames through every variant: outputs sane and identical bit for bit.
void expectSameOutput(const Frame& f, const Frame& canonical, const std::string& what) {
  for (const auto& [name, settings] : variants()) {
    SCOPED_TRACE(what + ", " + name);
    const Result a = run(f, settings), b = run(canonical, settings);
    EXPECT_EQ(expectSane(a, name), 0);
    EXPECT_TRUE(sameBits(a.rgba, b.rgba)) << "reflection differs from the canonical frame's";
    EXPECT_TRUE(sameBits(a.distance, b.distance)) << "distance differs from the canonical frame's";
  }
}

// The base frame of the value tests: spheres on a mirror floor with stripes of roughness 0, 0.3
// and 0.6, so the mirror, glossy and reuse paths all run.
Frame baseFrame(int width = 64, int height = 36) {
  const Scene scene = makeScene("spheres_on_mirror");
  const Camera camera = makeCamera(scene.view, width, height);
  Frame f = frameOf(renderGBuffer(scene, camera), camera);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (f.depth.at(x, y, 0) < 1e9f) f.roughness.at(x, y, 0) = 0.3f * float((x / 6) % 3);
  return f;
}

// The pixels the value tests make hostile: every 5th surface pixel in scan order (sky too where
// `sky` is set), so hostile pixels sit among ordinary neighbours that reuse and filter them.
template <class F>
void forPattern(Frame& f, F&& change, bool sky = false) {
  int k = 0;
  for (int y = 0; y < f.depth.height; ++y)
    for (int x = 0; x < f.depth.width; ++x)
      if ((sky || f.depth.at(x, y, 0) < 1e9f) && k++ % 5 == 0) change(x, y);
}

// ------------------------------------------------------------------------------------------------
// Hostile values

TEST(ExtremeValues, RoughnessReadsAsClampedWithNaNAsOne) {
  const Frame base = baseFrame();
  // (value, what it must be equivalent to): below the mirror threshold is the mirror, above 1 is
  // 1, negative is 0, NaN is 1 (documented in setup.cl).
  const std::pair<float, float> cases[] = {{1e-7f, 0.0f}, {FLT_MIN / 4, 0.0f}, {1.5f, 1.0f}, {kInf, 1.0f},
                                           {-1.0f, 0.0f}, {-kInf, 0.0f},       {kNaN, 1.0f}};
  for (const auto& c0 : cases) {
    const float value = c0.first, canonical = c0.second;  // named copies: lambdas capture them
    Frame f = base, c = base;
    forPattern(f, [&](int x, int y) { f.roughness.at(x, y, 0) = value; });
    forPattern(c, [&](int x, int y) { c.roughness.at(x, y, 0) = canonical; });
    expectSameOutput(f, c, "roughness " + std::to_string(value));
  }
  // Exactly 0 and exactly 1 everywhere: the ends of the GGX range.
  for (float r : {0.0f, 1.0f}) {
    Frame f = base;
    std::fill(f.roughness.data.begin(), f.roughness.data.end(), r);
    for (const auto& [name, settings] : variants()) EXPECT_EQ(expectSane(run(f, settings), name), 0) << r;
  }
}

// World normals with N.V = c exactly (in double) for the pixel's view direction.
Frame grazingFrame(double c, float roughness) {
  Frame f = baseFrame();
  const Scene scene = makeScene("spheres_on_mirror");
  for (int y = 0; y < f.depth.height; ++y)
    for (int x = 0; x < f.depth.width; ++x) {
      if (!(f.depth.at(x, y, 0) < 1e9f)) continue;
      const dvec3 o = -primaryRay(f.camera, x + 0.5, y + 0.5).direction;
      const dvec3 t = glm::normalize(glm::cross(o, dvec3(0.3, 1, 0.2)));
      const dvec3 n = c * o + std::sqrt(1 - c * c) * t;
      for (int k = 0; k < 3; ++k) f.normal.at(x, y, k) = float(n[k]);
      f.roughness.at(x, y, 0) = roughness;
    }
  return f;
}

TEST(ExtremeValues, MetalSmoothAtGrazingView) {
  for (double c : {1e-3, 1e-6, 1e-7, 0.0, -1e-6, -1e-3}) {
    for (float roughness : {0.0f, 0.5f}) {
      const Frame f = grazingFrame(c, roughness);
      for (const auto& [name, settings] : variants()) {
        SCOPED_TRACE("N.V " + std::to_string(c) + ", roughness " + std::to_string(roughness) + ", " + name);
        const Result r = run(f, settings);
        EXPECT_EQ(expectSane(r, name), 0);
        // Facing away from the viewer: no reflection is defined, A = 0. (At |N.V| <= 1e-6 the
        // sign is below float's resolution of the normal, so only finiteness is asserted there.)
        if (c < -1e-4) {
          int lit = 0;
          for (int i = 0; i < f.depth.width * f.depth.height; ++i) lit += r.rgba.data[size_t(i) * 4 + 3] > 0.0f;
          EXPECT_EQ(lit, 0);
        }
      }
    }
  }
}

TEST(ExtremeValues, NormalsAreDirectionsAtAnyScale) {
  const Frame base = baseFrame();
  // Powers of two scale exactly, so the output must not change by a bit: huge (2^100) and tiny
  // (2^-100) normals are directions like any other.
  for (float scale : {std::ldexp(1.0f, 100), std::ldexp(1.0f, -100)}) {
    Frame f = base;
    for (float& v : f.normal.data) v *= scale;
    expectSameOutput(f, base, "normals scaled by " + std::to_string(std::log2(scale)) + " octaves");
  }
  // Any other scale: the same up to rounding of the normalisation. Denormal normals (2^-140) keep
  // only the top 10 bits or so of each component: still directions, a few hits move.
  for (float scale : {7.3f, std::ldexp(1.0f, -140)}) {
    Frame f = base;
    for (float& v : f.normal.data) v *= scale;
    const auto mirror = variants()[0].second;
    const Result a = run(f, mirror), b = run(base, mirror);
    EXPECT_EQ(expectSane(a, "mirror"), 0);
    int differ = 0, litA = 0, litB = 0;
    for (size_t i = 0; i < a.rgba.data.size(); ++i) differ += std::abs(a.rgba.data[i] - b.rgba.data[i]) > 1e-3f;
    for (size_t i = 3; i < a.rgba.data.size(); i += 4) litA += a.rgba.data[i] > 0, litB += b.rgba.data[i] > 0;
    EXPECT_LE(differ, int(a.rgba.data.size() / (scale > 1 ? 100 : 20))) << "normals scaled by " << scale;
    EXPECT_NEAR(litA, litB, litB / 20) << "normals scaled by " << scale;
  }
  // Zero, NaN and infinite normals: the pixel reflects nothing (and its neighbours are unharmed:
  // every output stays sane); facing away from the viewer: nothing either.
  const std::pair<const char*, std::function<void(float*)>> broken[] = {
      {"zero", [](float* n) { n[0] = n[1] = n[2] = 0.0f; }},
      {"NaN", [](float* n) { n[1] = kNaN; }},
      {"all NaN", [](float* n) { n[0] = n[1] = n[2] = kNaN; }},
      {"infinite", [](float* n) { n[0] = kInf; }},
      {"-infinite", [](float* n) { n[2] = -kInf; }},
      {"facing away", [](float* n) { n[0] = -n[0], n[1] = -n[1], n[2] = -n[2]; }},
  };
  for (const auto& wc : broken) {
    const char* what = wc.first;
    const auto& change = wc.second;
    Frame f = base;
    std::vector<std::pair<int, int>> hit;
    forPattern(f, [&](int x, int y) {
      change(&f.normal.at(x, y, 0));
      hit.emplace_back(x, y);
    });
    for (const auto& [name, settings] : variants()) {
      SCOPED_TRACE(std::string(what) + " normals, " + name);
      const Result r = run(f, settings);
      EXPECT_EQ(expectSane(r, name), 0);
      int lit = 0;
      for (const auto& [x, y] : hit) lit += r.rgba.at(x, y, 3) != 0.0f || r.distance.at(x, y, 0) != 0.0f;
      EXPECT_EQ(lit, 0) << "pixels with " << what << " normals reflect something";
    }
  }
}

TEST(ExtremeValues, UnusableDepthIsSkyBitForBit) {
  for (bool infiniteFar : {false, true}) {
    Frame base = baseFrame();
    if (infiniteFar) {
      base.camera.projection = glm::infinitePerspective(glm::radians(45.0), 64.0 / 36.0, base.camera.nearPlane);
      base.camera.farPlane = INFINITY;
    }
    const float nearPlane = float(base.camera.nearPlane);
    std::vector<float> hostile = {
        0.0f, -0.0f, -1.0f, -FLT_MAX, kNaN, kInf, -kInf, 1e-40f, FLT_MIN, nearPlane * 0.999f, 1e10f, 2e10f, FLT_MAX};
    if (!infiniteFar) hostile.push_back(float(base.camera.farPlane) * 1.0001f);
    for (float value : hostile) {
      Frame f = base, sky = base;
      std::vector<std::pair<int, int>> changed;
      forPattern(f, [&](int x, int y) {
        f.depth.at(x, y, 0) = value;
        sky.depth.at(x, y, 0) = 1e10f;
        changed.emplace_back(x, y);
      });
      std::ostringstream what;
      what << "depth " << value << (infiniteFar ? " (infinite far plane)" : "");
      expectSameOutput(f, sky, what.str());
      const Result r = run(f, variants()[0].second);
      for (const auto& [x, y] : changed) {
        ASSERT_EQ(r.rgba.at(x, y, 3), 0.0f) << what.str();
        ASSERT_EQ(r.distance.at(x, y, 0), 0.0f) << what.str();
      }
    }
  }
}

TEST(ExtremeValues, ColourRuleNaNZeroNegativeZeroClampAt1e20) {
  const Frame base = baseFrame();
  const std::pair<float, float> cases[] = {{kNaN, 0.0f},  {-5.0f, 0.0f},  {-kInf, 0.0f},   {-0.0f, 0.0f},
                                           {kInf, 1e20f}, {1e30f, 1e20f}, {FLT_MAX, 1e20f}};
  for (const auto& c0 : cases) {
    const float value = c0.first, canonical = c0.second;  // named copies: lambdas capture them
    Frame f = base, c = base;
    forPattern(
        f, [&](int x, int y) { f.color.at(x, y, (x + y) % 3) = value; }, true);
    forPattern(
        c, [&](int x, int y) { c.color.at(x, y, (x + y) % 3) = canonical; }, true);
    expectSameOutput(f, c, "colour " + std::to_string(value));
  }
  // Everything at 1e30: mirror hits carry exactly the clamp, 1e20, times A; those through a
  // surface's back (kernels/trace.cl hit_pixel) are black whatever the colour.
  Frame f = base;
  std::fill(f.color.data.begin(), f.color.data.end(), 1e30f);
  TraceSettings mirror = variants()[0].second;
  mirror.edgeFade = 0.0f;
  const Result r = run(f, mirror);
  int hits = 0;
  for (int i = 0; i < f.depth.width * f.depth.height; ++i) {
    const float a = r.rgba.data[size_t(i) * 4 + 3];
    const float* rgb = &r.rgba.data[size_t(i) * 4];
    if (a <= 0.0f || (rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f)) continue;
    ++hits;
    for (int c = 0; c < 3; ++c) ASSERT_FLOAT_EQ(rgb[c], 1e20f * a);
  }
  EXPECT_GT(hits, 50);
  for (const auto& [name, settings] : variants()) EXPECT_EQ(expectSane(run(f, settings), name), 0);
}

// Every channel of many pixels replaced by something hostile at once.
TEST(ExtremeValues, RandomHostileGBuffersStaySane) {
  const float values[] = {kNaN,     kInf,  -kInf,  0.0f,   -0.0f, 1e-40f, -1e-40f, FLT_MAX,
                          -FLT_MAX, 1e30f, -1e30f, 1e-30f, 1e10f, -1.0f,  0.5f,    1.0f};
  const Frame base = baseFrame(48, 32);
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, int(std::size(values)) - 1), channel(0, 7);
    std::bernoulli_distribution hostile(0.3);
    Frame f = base;
    for (int y = 0; y < f.depth.height; ++y)
      for (int x = 0; x < f.depth.width; ++x) {
        if (!hostile(rng)) continue;
        const int c = channel(rng);
        const float v = values[pick(rng)];
        if (c < 3)
          f.color.at(x, y, c) = v;
        else if (c < 6)
          f.normal.at(x, y, c - 3) = v;
        else if (c == 6)
          f.depth.at(x, y, 0) = v;
        else
          f.roughness.at(x, y, 0) = v;
      }
    for (const auto& [name, settings] : variants()) EXPECT_EQ(expectSane(run(f, settings), name), 0) << "seed " << seed;
  }
}

// ------------------------------------------------------------------------------------------------
// Geometry against exact reflections

// Colour that names its pixel, so the reflection's RGB tells which pixel a ray hit.
void encodePixels(Frame& f) {
  for (int y = 0; y < f.color.height; ++y)
    for (int x = 0; x < f.color.width; ++x) {
      f.color.at(x, y, 0) = float(x) + 0.5f;
      f.color.at(x, y, 1) = float(y) + 0.5f;
      f.color.at(x, y, 2) = 1.0f;
    }
}

struct Agreement {
  size_t visible = 0, visibleOk = 0, miss = 0, missOk = 0;
  std::vector<std::string> bad;
  std::string summary() const {
    std::ostringstream o;
    o << "visible " << visibleOk << "/" << visible << " on the right pixel, sky/off-screen " << missOk << "/" << miss
      << " missed";
    for (size_t i = 0; i < bad.size() && i < 12; ++i) o << "\n  " << bad[i];
    return o.str();
  }
};

// The mirror path on `scene` seen by `camera` (any projection the truth can ray-cast: `truthCamera`
// renders the G-buffer, `camera` is what the pipeline gets; they differ only in depth layout).
// Visible reflections must land within a pixel of the exact hit (A = 1, edge fade off), rays
// that find nothing on screen must report A = 0; every output must be sane.
struct Truth {
  AnalyticGBuffer g;
  MirrorTruth truth;
};

Truth renderTruth(const Scene& scene, const Camera& camera) {
  Truth t{renderGBuffer(scene, camera), {}};
  t.truth = exactMirrorReflection(scene, camera, t.g);
  return t;
}

Agreement agreeWithTruth(const Truth& t, const Camera& camera, Tracer tracer = Tracer::HiZ);

Agreement agreeWithTruth(const Scene& scene, const Camera& truthCamera, const Camera& camera,
                         Tracer tracer = Tracer::HiZ) {
  return agreeWithTruth(renderTruth(scene, truthCamera), camera, tracer);
}

Agreement agreeWithTruth(const Truth& rendered, const Camera& camera, Tracer tracer) {
  const AnalyticGBuffer& g = rendered.g;
  const MirrorTruth& truth = rendered.truth;
  Frame f = frameOf(g, camera);
  encodePixels(f);
  TraceSettings s = qualityPreset("medium");
  s.mirrorRoughness = 1.0f;
  s.edgeFade = 0.0f;
  s.edgeColors = false;  // the colour names the pixel hit
  s.tracer = tracer;
  // Hi-Z keeps the preset's iteration cap (512), 8192-pixel strips included. The DDA and linear
  // tracers visit every pixel, so 512 steps reach 512 pixels: on the strips below (hits 565 to
  // 8000 pixels away) they would find nothing; they get enough steps to cross the screen.
  if (tracer != Tracer::HiZ) s.maxIterations = 1 << 16;
  const Result r = run(f, s);
  EXPECT_EQ(expectSane(r, "mirror"), 0);
  Agreement a;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const MirrorSample& t = truth.at(x, y);
      const float alpha = r.rgba.at(x, y, 3);
      const double depth = g.depth.at(x, y, 0);
      if (!(depth >= camera.nearPlane && depth <= camera.farPlane)) continue;  // no surface for SSR
      std::ostringstream o;
      if (t.cls == ReflectionClass::Visible) {
        ++a.visible;
        const int hx = alpha > 0 ? int(std::floor(r.rgba.at(x, y, 0) / alpha)) : -1;
        const int hy = alpha > 0 ? int(std::floor(r.rgba.at(x, y, 1) / alpha)) : -1;
        const double relD = std::abs(r.distance.at(x, y, 0) - t.hit.t) / t.hit.t;
        const bool ok = alpha > 0.999f && std::abs(hx - int(std::floor(t.screen.x))) <= 1 &&
                        std::abs(hy - int(std::floor(t.screen.y))) <= 1 && relD <= 0.02 + 2 * t.distanceSpread;
        a.visibleOk += ok;
        if (!ok) {
          o << "(" << x << "," << y << ") expected hit at " << t.screen.x << "," << t.screen.y << " dist " << t.hit.t
            << ", got A " << alpha << " pixel " << hx << "," << hy << " dist " << r.distance.at(x, y, 0);
          a.bad.push_back(o.str());
        }
      } else if (t.cls == ReflectionClass::Sky || t.cls == ReflectionClass::OffScreen) {
        ++a.miss;
        a.missOk += alpha == 0.0f;
        if (alpha != 0.0f) {
          o << "(" << x << "," << y << ") " << className(t.cls) << " got A " << alpha << " pixel "
            << r.rgba.at(x, y, 0) / alpha << "," << r.rgba.at(x, y, 1) / alpha;
          a.bad.push_back(o.str());
        }
      }
    }
  return a;
}

// Rates the extreme cases must keep. These scenes run at 160x90 and smaller, where a pixel is 3x
// wider than in the 480x270 mirror test of the analytic scenes (97%): more exact hits fall within
// a pixel of a silhouette, where a per-pixel tracer lands on the neighbouring surface, so 93% of
// the visible reflections must be on the right pixel (measured 95-98%). Misses: a ray that ends
// just past a surface's edge passes behind its last pixel within the thickness and is reported
// as a hit there, by design (TraceSettings::thicknessRelative); in the open corridors below that
// is 6% of the misses (measured 94.3%, elsewhere >= 98.8%), so 93% too.
constexpr double kVisibleRate = 0.93, kMissRate = 0.93;

void expectAgreement(const Agreement& a, const std::string& what, size_t minVisible = 1,
                     double visibleRate = kVisibleRate) {
  std::cout << what << ": " << a.summary().substr(0, a.summary().find('\n')) << "\n";
  EXPECT_GE(a.visible, minVisible) << what << ": the case must have reflections to check";
  EXPECT_GE(double(a.visibleOk), visibleRate * double(a.visible)) << what << ": " << a.summary();
  EXPECT_GE(double(a.missOk), kMissRate * double(a.miss)) << what << ": " << a.summary();
}

// An extreme configuration of a scene the standard camera also sees: as good as that, to within
// half a percent.
void expectAsGoodAs(const Agreement& a, const Agreement& baseline, const std::string& what) {
  expectAgreement(a, what, baseline.visible / 2);
  EXPECT_GE(double(a.visibleOk) / double(a.visible), double(baseline.visibleOk) / double(baseline.visible) - 0.005)
      << what << ": " << a.summary();
  EXPECT_GE(double(a.missOk) / double(a.miss), double(baseline.missOk) / double(baseline.miss) - 0.005)
      << what << ": " << a.summary();
}

Camera withProjection(Camera c, const glm::dmat4& projection, double nearPlane, double farPlane) {
  c.projection = projection;
  c.nearPlane = nearPlane;
  c.farPlane = farPlane;
  return c;
}

Scene scaled(Scene s, double k) {
  for (Primitive& p : s.primitives) {
    p.center *= k;
    p.halfSize *= k;
    p.radius *= k;
    p.material.period *= k;
  }
  s.view.eye *= k;
  s.view.target *= k;
  return s;
}

// A mirror turned `tiltDegrees` about +Y from facing the camera (at the origin, looking down -Z)
// 10 units ahead, and boxes behind the camera that its reflection would show.
Scene mirrorFacingCamera(double tiltDegrees) {
  Scene s;
  const double t = tiltDegrees * kPi / 180.0;
  s.primitives = {rectangle("mirror", dvec3(0, 0, -10), dvec3(std::sin(t), 0, std::cos(t)), 30, 30, Material{}),
                  box("behind_left", dvec3(-3, 0, 6), dvec3(1.5), 20, Material{dvec3(0.9, 0.3, 0.2)}),
                  box("behind_right", dvec3(4, 1, 8), dvec3(2.0), -10, Material{dvec3(0.2, 0.8, 0.3)}),
                  sphere("behind_far", dvec3(0, 0, 15), 4.0, Material{dvec3(0.3, 0.4, 0.9)})};
  s.view.eye = dvec3(0.0);
  s.view.target = dvec3(0, 0, -1);
  return s;
}

TEST(ExtremeGeometry, RaysTowardTheCameraAndReflectionsOfPointsBehindIt) {
  for (double tilt : {0.0, 10.0, 25.0}) {
    for (bool ortho : {false, true}) {
      SCOPED_TRACE("tilt " + std::to_string(tilt) + (ortho ? " orthographic" : " perspective"));
      const Scene scene = mirrorFacingCamera(tilt);
      Camera camera = makeCamera(scene.view, 81, 61);  // odd: the centre ray is exactly head-on
      if (ortho) camera.projection = glm::ortho(-8.1, 8.1, -6.1, 6.1, 0.1, 1000.0);
      const AnalyticGBuffer g = renderGBuffer(scene, camera);
      const MirrorTruth truth = exactMirrorReflection(scene, camera, g);
      // Every reflected ray runs back toward the camera and out through the near plane (or
      // past the eye, orthographic): the truth finds the boxes behind the camera, off screen.
      if (!(ortho && tilt > 20)) EXPECT_GT(truth.count(ReflectionClass::OffScreen), 0u);  // there: sky
      EXPECT_EQ(truth.count(ReflectionClass::Visible), 0u);
      Frame f = frameOf(g, camera), glossy = f;
      std::fill(glossy.roughness.data.begin(), glossy.roughness.data.end(), 0.5f);
      for (const auto& [name, settings] : variants()) {
        const Result r = run(f, settings);
        const Result rg = run(glossy, settings);
        EXPECT_EQ(expectSane(rg, name + " glossy"), 0);
        for (int i = 0; i < camera.width * camera.height; ++i)
          ASSERT_EQ(rg.rgba.data[size_t(i) * 4 + 3], 0.0f) << name << " glossy: nothing on screen can be reflected";
        EXPECT_EQ(expectSane(r, name), 0);
        int lit = 0;
        for (int i = 0; i < camera.width * camera.height; ++i) lit += r.rgba.data[size_t(i) * 4 + 3] > 0.0f;
        EXPECT_EQ(lit, 0) << name << ": nothing on screen can be reflected";
      }
    }
  }
}

// A 45-degree mirror straight ahead turns the central rays parallel to the image plane, onto a
// wall to the right at the same depth.
TEST(ExtremeGeometry, RaysParallelToTheImagePlane) {
  Scene scene;
  scene.primitives = {rectangle("mirror", dvec3(0, 0, -10), glm::normalize(dvec3(1, 0, 1)), 2.5, 2.5, Material{}),
                      rectangle("wall", dvec3(3, 0, -10), dvec3(-1, 0, 0), 3, 4, Material{dvec3(0.9, 0.6, 0.3)})};
  scene.view.eye = dvec3(0.0);
  scene.view.target = dvec3(0, 0, -1);
  scene.view.fovYDegrees = 40;
  const Camera camera = makeCamera(scene.view, 121, 91);
  for (Tracer tracer : {Tracer::HiZ, Tracer::DDA, Tracer::Linear}) {
    const Agreement a = agreeWithTruth(scene, camera, camera, tracer);
    expectAgreement(a, "parallel to the image plane, tracer " + std::to_string(int(tracer)), 500);
  }
}

TEST(ExtremeGeometry, NearFarRatiosFrom1e4To1e11) {
  const Scene scene = makeScene("spheres_on_mirror");
  const Camera standard = makeCamera(scene.view, 160, 90);  // near 0.1, far 1000
  const Agreement baseline = agreeWithTruth(scene, standard, standard);
  expectAgreement(baseline, "near 0.1 far 1000 (baseline)", 500);
  struct Planes {
    double nearPlane, farPlane;
  };
  for (const Planes& p : {Planes{1e-4, 1.0e3}, Planes{1e-4, 1e7}, Planes{1e-2, 1e5}, Planes{1.0, 1e7},
                          Planes{1e-4, INFINITY}, Planes{2.0, 30.0}}) {
    ViewParams v = scene.view;
    v.nearPlane = p.nearPlane;
    v.farPlane = std::isinf(p.farPlane) ? 1e30 : p.farPlane;
    Camera camera = makeCamera(v, 160, 90);
    if (std::isinf(p.farPlane))
      camera = withProjection(camera, glm::infinitePerspective(glm::radians(v.fovYDegrees), 160.0 / 90.0, p.nearPlane),
                              p.nearPlane, INFINITY);
    std::ostringstream what;
    what << "near " << p.nearPlane << " far " << p.farPlane;
    expectAsGoodAs(agreeWithTruth(scene, camera, camera), baseline, what.str());
  }
}

TEST(ExtremeGeometry, SceneScaleFrom1e3To1e4) {
  const Scene standard = makeScene("mirror_wall");
  const Camera standardCamera = makeCamera(standard.view, 160, 90);
  const Agreement baseline = agreeWithTruth(standard, standardCamera, standardCamera);
  for (double k : {1e-3, 1e4}) {
    const Scene scene = scaled(standard, k);
    ViewParams v = scene.view;
    v.nearPlane = 0.1 * k;
    v.farPlane = 1000 * k;
    const Camera camera = makeCamera(v, 160, 90);
    expectAsGoodAs(agreeWithTruth(scene, camera, camera), baseline, "scene scaled by " + std::to_string(k));
  }
}

// The depth row of a projection in each layout deriveClipPlanes accepts (row 3 = 0, 0, A, B).
struct Layout {
  const char* name;
  bool perspective;
  double (*a)(double n, double f);
  double (*b)(double n, double f);
  bool infinite;
};
const Layout kLayouts[] = {
    {"GL", true, [](double n, double f) { return -(f + n) / (f - n); },
     [](double n, double f) { return -2 * f * n / (f - n); }, false},
    {"GL infinite", true, [](double, double) { return -1.0; }, [](double n, double) { return -2 * n; }, true},
    {"[0,1]", true, [](double n, double f) { return -f / (f - n); },
     [](double n, double f) { return -f * n / (f - n); }, false},
    {"[0,1] infinite", true, [](double, double) { return -1.0; }, [](double n, double) { return -n; }, true},
    {"[0,1] reversed", true, [](double n, double f) { return n / (f - n); },
     [](double n, double f) { return f * n / (f - n); }, false},
    {"[0,1] reversed infinite", true, [](double, double) { return 0.0; }, [](double n, double) { return n; }, true},
    {"GL reversed", true, [](double n, double f) { return (f + n) / (f - n); },
     [](double n, double f) { return 2 * f * n / (f - n); }, false},
    {"GL reversed infinite", true, [](double, double) { return 1.0; }, [](double n, double) { return 2 * n; }, true},
    {"ortho GL", false, [](double n, double f) { return -2 / (f - n); },
     [](double n, double f) { return -(f + n) / (f - n); }, false},
    {"ortho [0,1] reversed", false, [](double n, double f) { return 1 / (f - n); },
     [](double n, double f) { return f / (f - n); }, false},
    {"ortho GL reversed", false, [](double n, double f) { return 2 / (f - n); },
     [](double n, double f) { return (f + n) / (f - n); }, false},
};

glm::dmat4 withDepthRow(glm::dmat4 m, const Layout& l, double n, double f) {
  m[2][2] = l.a(n, f);  // glm: m[column][row]
  m[3][2] = l.b(n, f);
  return m;
}

TEST(DeriveClipPlanesLayouts, ExactOrContainingTheTrueRange) {
  const glm::dmat4 persp = glm::frustum(-0.07, 0.13, -0.05, 0.06, 0.1, 10.0);  // off-centre too
  const glm::dmat4 ortho = glm::ortho(-3.0, 5.0, -2.0, 2.5, 0.1, 10.0);
  for (const Layout& l : kLayouts) {
    for (auto [n, f] : {std::pair{1e-4, 1e7}, {0.1, 100.0}, {1.0, 1e4}, {2.5, 3.0}, {1e-4, 1.0}}) {
      SCOPED_TRACE(std::string(l.name) + " near " + std::to_string(n) + " far " + std::to_string(f));
      const glm::dmat4 m = withDepthRow(l.perspective ? persp : ortho, l, n, f);
      double dn = 0, df = 0;
      ASSERT_NO_THROW(deriveClipPlanes(m, dn, df));
      const std::string name = l.name;
      const double trueFar = l.infinite ? INFINITY : f;
      // Documented inexact readings: a standard-Z [0,1] perspective reads as OpenGL (near
      // n f / (2 f - n)); [0,1] reversed with f <= 2n reads as GL reversed (far larger);
      // orthographic [0,1] reversed reads as GL reversed (far 2 f - n).
      // Rounding: A +- 1 cancels to about f / n ulps (1e-5 relative at f / n = 1e11), and
      // orthographic planes are only accurate relative to far.
      const double nearTol = 1e-9 * n + (l.perspective ? 0.0 : 1e-12 * f);
      const double farTol = std::max(1e-9, 1e-15 * f / n) * f;
      if (name == "[0,1]" || name == "[0,1] infinite") {
        EXPECT_NEAR(dn, l.infinite ? n / 2 : n * f / (2 * f - n), nearTol);
      } else {
        EXPECT_NEAR(dn, n, nearTol);
      }
      if (std::isinf(trueFar)) {
        EXPECT_EQ(df, INFINITY);
      } else if (name == "ortho [0,1] reversed") {
        EXPECT_NEAR(df, 2 * f - n, farTol);
      } else if (name == "[0,1] reversed" && f <= 2 * n) {
        EXPECT_GE(df, f);
      } else {
        EXPECT_NEAR(df, f, farTol);
      }
      // The derived range always contains the true one (up to that rounding).
      EXPECT_LE(dn, n + nearTol);
      EXPECT_GE(df, trueFar - farTol);
    }
  }
  double n = 0, f = 0;
  glm::dmat4 oblique = glm::perspective(1.0, 1.5, 0.1, 10.0);
  oblique[0][2] = 0.3;  // row 3 depends on x
  EXPECT_THROW(deriveClipPlanes(oblique, n, f), Error);
  glm::dmat4 noDepth = glm::perspective(1.0, 1.5, 0.1, 10.0);
  noDepth[3][2] = 0.0;
  EXPECT_THROW(deriveClipPlanes(noDepth, n, f), Error);
}

// The same frame handed over with its projection in every accepted depth layout: the kernels
// use the projection's x, y and w rows and the given planes, so the reflections must agree.
TEST(ExtremeGeometry, DepthLayoutsGiveTheSameReflections) {
  for (bool perspective : {true, false}) {
    const Scene scene = makeScene("spheres_on_mirror");
    Camera gl = makeCamera(scene.view, 160, 90);
    const double n = 0.1, f = 1000.0;
    if (!perspective) gl.projection = glm::ortho(-8.0, 8.0, -4.5, 4.5, n, f);
    const AnalyticGBuffer g = renderGBuffer(scene, gl);
    Frame base = frameOf(g, gl);
    TraceSettings mirror = variants()[0].second;
    const Result expected = run(base, mirror);
    const Result expectedGlossy = run(base, qualityPreset("medium"));
    int checked = 0;
    for (const Layout& l : kLayouts) {
      if (l.perspective != perspective) continue;
      ++checked;
      SCOPED_TRACE(l.name);
      Frame frame = base;
      frame.camera.projection = withDepthRow(gl.projection, l, n, f);
      // Planes as the camera JSON loader derives them when the file gives none.
      ASSERT_NO_THROW(deriveClipPlanes(frame.camera.projection, frame.camera.nearPlane, frame.camera.farPlane));
      ASSERT_NO_THROW(validateCamera(frame.camera, l.name));
      for (const auto& [result, reference, label] :
           {std::tuple{run(frame, mirror), &expected, "mirror"},
            std::tuple{run(frame, qualityPreset("medium")), &expectedGlossy, "medium"}}) {
        EXPECT_EQ(expectSane(result, label), 0);
        int differ = 0, lit = 0;
        for (size_t i = 0; i < result.rgba.data.size(); ++i)
          differ += std::abs(result.rgba.data[i] - reference->rgba.data[i]) > 2e-3f * (1 + reference->rgba.data[i]);
        for (size_t i = 3; i < result.rgba.data.size(); i += 4) lit += result.rgba.data[i] > 0;
        // Float rounding of another inverse matrix can move a hit that grazes a pixel edge.
        EXPECT_LE(differ, int(result.rgba.data.size() / 200)) << label;
        EXPECT_GT(lit, 1000) << label;
      }
    }
    EXPECT_GE(checked, 3);
  }
}

TEST(ExtremeGeometry, OrthographicCameras) {
  for (const char* name : {"spheres_on_mirror", "mirror_wall"}) {
    const Scene scene = makeScene(name);
    Camera camera = makeCamera(scene.view, 160, 90);
    camera.projection = glm::ortho(-8.0, 8.0, -4.5, 4.5, 0.1, 1000.0);
    expectAgreement(agreeWithTruth(scene, camera, camera), std::string("orthographic ") + name, 500);
  }
}

TEST(ExtremeGeometry, OffCentreProjections) {
  const Scene scene = makeScene("spheres_on_mirror");
  Camera camera = makeCamera(scene.view, 160, 90);
  const double n = 0.1;
  // Lens shift: the frustum's centre well off the optical axis, right and up, then left and down.
  for (auto [l, r, b, t] : {std::tuple{-0.02, 0.1, -0.02, 0.0475}, std::tuple{-0.1, 0.02, -0.05, 0.0175}}) {
    camera.projection = glm::frustum(l * n / 0.1, r * n / 0.1, b * n / 0.1, t * n / 0.1, n, 1000.0);
    expectAgreement(agreeWithTruth(scene, camera, camera), "shifted perspective", 300);
  }
  camera.projection = glm::ortho(-3.0, 13.0, -2.0, 7.0, 0.1, 1000.0);
  expectAgreement(agreeWithTruth(scene, camera, camera), "shifted orthographic", 300);
}

// Two parallel mirrors along the view: walls x = -2 and x = +2 (a horizontal corridor) or
// floor and ceiling (vertical), the camera at the origin looking down -Z between them, the far
// end open to the sky. Reflections cross the screen along the strip; its middle is sky, so rays
// climb to the top of the HZB on their way.
Scene corridor(bool horizontal) {
  Scene s;
  const dvec3 axis = horizontal ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  // Rectangle axes: normal +-X gives u = -+Y, v = Z; normal +-Y gives u = X, v = Z.
  s.primitives = {rectangle("mirror_a", -2.0 * axis + dvec3(0, 0, -30), axis, 5, 28, Material{dvec3(0.8, 0.5, 0.3)}),
                  rectangle("mirror_b", 2.0 * axis + dvec3(0, 0, -30), -axis, 5, 28, Material{dvec3(0.3, 0.5, 0.8)})};
  s.view.eye = dvec3(0.0);
  s.view.target = dvec3(0, 0, -1);
  return s;
}

Camera corridorCamera(int width, int height) {
  // 90 degrees across the long side of the strip.
  const double longSide = std::max(width, height), shortSide = std::min(width, height);
  const double halfTall = width >= height ? shortSide / longSide : 1.0;
  Camera c;
  c.width = width;
  c.height = height;
  c.view = glm::dmat4(1.0);
  c.projection = glm::perspective(2 * std::atan(halfTall), double(width) / height, 0.1, 1000.0);
  c.nearPlane = 0.1;
  c.farPlane = 1000.0;
  return c;
}

TEST(ExtremeResolutions, OnePixel) {
  // 1x1: the only pixel's ray leaves the screen at once.
  const Scene scene = makeScene("spheres_on_mirror");
  const Camera camera = makeCamera(scene.view, 1, 1);
  Frame f = frameOf(renderGBuffer(scene, camera), camera);
  for (const auto& [name, settings] : variants()) {
    const Result r = run(f, settings);
    EXPECT_EQ(expectSane(r, name), 0);
    EXPECT_EQ(r.rgba.at(0, 0, 3), 0.0f) << name;
  }
}

// Strips one pixel (or three) thick and up to 8192 long: pixel coordinates where float has
// 1/1024 pixel left, and an HZB of 14 levels whose top cells span the strip.
class ExtremeStrips : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(ExtremeStrips, HitsLandOnTheRightPixel) {
  const auto [w, h] = GetParam();
  const std::string what = std::to_string(w) + "x" + std::to_string(h) + " corridor";
  const Scene scene = corridor(w > h);
  const Camera camera = corridorCamera(w, h);
  const Truth truth = renderTruth(scene, camera);
  expectAgreement(agreeWithTruth(truth, camera), what, size_t(std::max(w, h) / 4));
  expectAgreement(agreeWithTruth(truth, camera, Tracer::DDA), what + " (DDA)", size_t(std::max(w, h) / 4));
  const Frame f = frameOf(truth.g, camera);
  for (const auto& [name, settings] : variants()) EXPECT_EQ(expectSane(run(f, settings), name), 0) << what;
}

INSTANTIATE_TEST_SUITE_P(Sizes, ExtremeStrips,
                         ::testing::Values(std::pair{257, 1}, std::pair{1, 257}, std::pair{8192, 3}, std::pair{3, 8192},
                                           std::pair{8191, 1}),
                         [](const auto& info) {
                           return std::to_string(info.param.first) + "x" + std::to_string(info.param.second);
                         });

// Odd primes. At 13x7 objects are a pixel or two wide and nearly every hit is at a silhouette:
// only sane output is asserted there; at 101x53 a pixel is 5x wider than at 480x270, 90%.
TEST(ExtremeResolutions, OddPrimes) {
  struct Size {
    int w, h;
  };
  for (Size s : {Size{13, 7}, Size{101, 53}, Size{307, 173}}) {
    const std::string what = std::to_string(s.w) + "x" + std::to_string(s.h);
    for (const char* name : {"spheres_on_mirror", "mirror_wall"}) {
      const Scene scene = makeScene(name);
      const Camera camera = makeCamera(scene.view, s.w, s.h);
      const Truth truth = renderTruth(scene, camera);
      const Agreement a = agreeWithTruth(truth, camera);
      if (s.w > 13) expectAgreement(a, what + " " + name, 100, s.w < 200 ? 0.90 : kVisibleRate);
      const Frame f = frameOf(truth.g, camera);
      for (const auto& [vname, settings] : variants()) EXPECT_EQ(expectSane(run(f, settings), vname), 0) << what;
    }
  }
}

// 8192x8192: about 13 GB of device buffers and 3.5 GB on the host, so it runs only on devices
// with 16 GiB (GPUs), or where SSRCL_TEST_HUGE is set (a CPU device with the memory). Everything
// is too rough to trace but a band of rows through the middle, whose hits must land on the
// right pixels.
TEST(ExtremeResolutions, Full8192Frame) {
  const unsigned long long needed = 16ull << 30;
  if (device().info().globalMemory < needed && !std::getenv("SSRCL_TEST_HUGE"))
    GTEST_SKIP() << "device '" << device().info().name << "' has " << (device().info().globalMemory >> 20)
                 << " MiB; an 8192x8192 frame needs about 16 GiB (SSRCL_TEST_HUGE=1 runs it anyway)";
  constexpr int kSize = 8192, kBand0 = 4090, kBand1 = 4102;
  const Scene scene = corridor(true);
  const Camera camera = corridorCamera(kSize, kSize);
  Frame f{camera, Image(kSize, kSize, 3), Image(kSize, kSize, 1), Image(kSize, kSize, 3), Image(kSize, kSize, 1)};
  encodePixels(f);
  std::vector<MirrorSample> truth(size_t(kSize) * (kBand1 - kBand0));
  // primaryRay() inverts the matrix per call: done once here for 67 million rays.
  const glm::dmat4 inv = glm::inverse(camera.projection * camera.view);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::dvec2 ndc(2.0 * (x + 0.5) / kSize - 1.0, 1.0 - 2.0 * (y + 0.5) / kSize);
      const glm::dvec4 a = inv * glm::dvec4(ndc, -1.0, 1.0), b = inv * glm::dvec4(ndc, 0.0, 1.0);
      Ray ray;
      ray.origin = dvec3(a) / a.w;
      ray.direction = glm::normalize(dvec3(b) / b.w - ray.origin);
      const Hit hit = intersect(scene, ray);
      f.depth.at(x, y, 0) = hit ? float(planarDepth(camera, hit.position)) : 1e10f;
      for (int c = 0; c < 3; ++c) f.normal.at(x, y, c) = hit ? float(hit.normal[c]) : 0.0f;
      const bool band = y >= kBand0 && y < kBand1;
      f.roughness.at(x, y, 0) = band ? 0.0f : 1.0f;
      if (band && hit) truth[size_t(y - kBand0) * kSize + x] = reflectAt(scene, camera, hit, ray.direction);
    }
  TraceSettings s = qualityPreset("medium");
  s.maxRoughness = 0.5f;
  s.edgeFade = 0.0f;
  s.edgeColors = false;  // the colour names the pixel hit
  const Result r = run(f, s);
  EXPECT_GT(r.times.tracedPixels, 0);
  EXPECT_LE(r.times.tracedPixels, (kBand1 - kBand0) * kSize);  // the band only: the rest is too rough
  Agreement a;
  for (int y = kBand0; y < kBand1; ++y)
    for (int x = 0; x < kSize; ++x) {
      const MirrorSample& t = truth[size_t(y - kBand0) * kSize + x];
      const float alpha = r.rgba.at(x, y, 3);
      if (t.cls != ReflectionClass::Visible) continue;
      ++a.visible;
      a.visibleOk += alpha > 0.999f && std::abs(int(r.rgba.at(x, y, 0) / alpha) - int(t.screen.x)) <= 1 &&
                     std::abs(int(r.rgba.at(x, y, 1) / alpha) - int(t.screen.y)) <= 1;
    }
  std::cout << "8192x8192 band: " << a.visibleOk << " of " << a.visible << " visible reflections on the right pixel\n";
  EXPECT_GE(a.visible, 50000u);
  EXPECT_GE(double(a.visibleOk), kVisibleRate * double(a.visible));
}

}  // namespace
