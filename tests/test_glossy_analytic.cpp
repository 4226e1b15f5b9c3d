// Glossy SSR on an analytic scene (a rough floor reflecting a constant-radiance panel) against
// quadrature truth (tests/support/glossy_truth.*), plus checks of the truth itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/geometric.hpp>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/pipeline.hpp"
#include "support/glossy_truth.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl::test;
using ggx::kPi;
using glm::dvec3;

// Small enough for the reference tracer on a 2-core CPU; the floor covers ~5600 pixels, the
// panel ~3100. 90 rows: the panel's top edge lies on a pixel boundary (makeGlossyScene).
constexpr int kWidth = 160, kHeight = 90;
// The panel (roughness 1) is above this, so it gets no rays of its own.
constexpr float kMaxRoughness = 0.9f;

// The panel with its top and side edges moved `pixels` outward on screen (inward if negative);
// the bottom edge stays on the floor.
Primitive movedPanel(const Scene& scene, const ssrcl::Camera& camera, double pixels) {
  Primitive p = scene.primitives[kGlossyPanel];
  const double top = p.center.y + p.halfSize.x, bottom = p.center.y - p.halfSize.x, side = p.halfSize.z;
  const auto screen = [&](double x, double y) { return projectToScreen(camera, dvec3(x, y, p.center.z)); };
  // Bisection for f(v) = target, f monotonic on [lo, hi].
  const auto solve = [](auto f, double target, double lo, double hi) {
    const bool rising = f(hi) > f(lo);
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((f(mid) < target) == rising ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  const double newTop = solve([&](double y) { return screen(0, y).y; }, screen(0, top).y - pixels, top - 1, top + 1);
  const double newSide =
      solve([&](double x) { return screen(x, top).x; }, screen(side, top).x + pixels, side - 1, side + 1);
  p.center.y = 0.5 * (bottom + newTop);
  p.halfSize.x = 0.5 * (newTop - bottom);
  p.halfSize.z = newSide;
  return p;
}

struct GlossyCase {
  double roughness = 0;
  Scene scene;
  ssrcl::Camera camera;
  AnalyticGBuffer g;
  GlossyTruth truth;
  // Truth for the panel half a pixel smaller / larger on screen: what an SSR that resolves the
  // panel's silhouette to within half a pixel may return (computed on first use).
  std::unique_ptr<GlossyTruth> shrunk, grown;
};

// The truth costs 0.7-3 s per roughness on 2 cores: computed once per process.
GlossyCase& glossyCase(double roughness) {
  static std::map<double, std::unique_ptr<GlossyCase>> cache;
  auto& c = cache[roughness];
  if (!c) {
    c = std::make_unique<GlossyCase>();
    c->roughness = roughness;
    c->scene = makeGlossyScene(roughness);
    c->camera = makeCamera(c->scene.view, kWidth, kHeight);
    c->g = renderGBuffer(c->scene, c->camera);
    c->truth = glossyTruth(c->scene, c->camera, c->g, kGlossyFloor, kGlossyPanel);
  }
  return *c;
}

void computeEnvelope(GlossyCase& c) {
  if (c.shrunk) return;
  for (double px : {-0.5, 0.5}) {
    Scene moved = c.scene;
    moved.primitives[kGlossyPanel] = movedPanel(c.scene, c.camera, px);
    auto t = std::make_unique<GlossyTruth>(glossyTruth(moved, c.camera, c.g, kGlossyFloor, kGlossyPanel));
    (px < 0 ? c.shrunk : c.grown) = std::move(t);
  }
}

std::string pixelName(int x, int y) { return "(" + std::to_string(x) + "," + std::to_string(y) + ")"; }

// ---------------------------------------------------------------------------------------------
// The truth, independently of SSR.

// The quadrature integrates ggx_reference.hpp's D and visible-normal density to 1.
TEST(GlossyTruth, GgxReferenceNormalizes) {
  const dvec3 z(0, 0, 1);
  for (double alpha : {1e-3, 0.0225, 0.09, 0.36, 1.0}) {
    const double d = integrateAround([&](const dvec3& h) { return ggx::ndf(h, alpha) * h.z; }, z, alpha,
                                     hemisphereClip(z), {}, Quadrature{});
    EXPECT_NEAR(d, 1.0, 1e-6) << "alpha " << alpha;
    for (double deg : {0.0, 30.0, 60.0, 80.0, 89.0}) {
      const double t = deg * kPi / 180;
      const dvec3 o(std::sin(t), 0, std::cos(t));
      const auto vndf = [&](const dvec3& h) {
        return ggx::smithG1(o, alpha) * glm::dot(o, h) * ggx::ndf(h, alpha) / o.z;
      };
      // Visible normals: n.h > 0 and o.h > 0, both clipped exactly so the integrand has no kink.
      const ArcClip hemi = hemisphereClip(z), facing = hemisphereClip(o);
      const ArcClip both = [&](const dvec3& m, const dvec3& e, double& lo, double& hi) {
        double l1, h1, l2, h2;
        if (!hemi(m, e, l1, h1) || !facing(m, e, l2, h2)) return false;
        lo = std::max(l1, l2);
        hi = std::min(h1, h2);
        return hi > lo;
      };
      // The interval's end switches between the two boundaries where they meet: +-(z x o).
      dvec3 e1, e2;
      planeAxes(z, e1, e2);
      const dvec3 meet = glm::cross(z, o);
      const double phi = std::atan2(glm::dot(meet, e2), glm::dot(meet, e1));
      const double integral = integrateAround(vndf, z, alpha, both, {phi, phi + kPi}, Quadrature{});
      EXPECT_NEAR(integral, 1.0, 1e-6) << "alpha " << alpha << " theta_o " << deg;
    }
  }
}

// The brute-force cross-check's (u1, u2) -> h map has density D cos theta_h: its Jacobian
// |dh/du1 x dh/du2| is 1 / (D cos theta_h), by central differences.
TEST(GlossyTruth, NdfStratificationJacobian) {
  for (double alpha : {0.0225, 0.09, 0.36, 1.0})
    for (double u1 : {0.05, 0.3, 0.7, 0.95})
      for (double u2 : {0.1, 0.6}) {
        const double e = 1e-6;
        const dvec3 d1 = (ndfHalfVector(alpha, u1 + e, u2) - ndfHalfVector(alpha, u1 - e, u2)) / (2 * e);
        const dvec3 d2 = (ndfHalfVector(alpha, u1, u2 + e) - ndfHalfVector(alpha, u1, u2 - e)) / (2 * e);
        const dvec3 h = ndfHalfVector(alpha, u1, u2);
        const double jac = glm::length(glm::cross(d1, d2)), expected = 1 / (ggx::ndf(h, alpha) * h.z);
        EXPECT_NEAR(glm::length(h), 1.0, 1e-12);
        EXPECT_NEAR(jac / expected, 1.0, 1e-6) << alpha << " " << u1 << " " << u2;
      }
}

// A ceiling covering the hemisphere up to 1e-6 rad above the horizon (where G2 ~ 0) is found by
// the whole lobe, whatever the roughness and view: the rectangle clip and the hemisphere
// integral agree. As alpha -> 0 nothing is lost to masking at moderate angles: total -> 1.
TEST(GlossyTruth, WholeHemisphereGivesOne) {
  const Primitive ceiling = rectangle("ceiling", dvec3(0.3, 1, -0.2), dvec3(0, 1, 0), 1e6, 1e6, Material{});
  const dvec3 n(0, 1, 0), p(0.0);
  for (double alpha : {1e-4, 0.0225, 0.09, 0.36, 1.0})
    for (double deg : {0.0, 20.0, 45.0, 70.0, 85.0}) {
      const double t = deg * kPi / 180;
      const dvec3 o = glm::normalize(dvec3(std::sin(t) * 0.6, std::cos(t), std::sin(t) * 0.8));
      const LobeFraction f = lobeFraction(p, n, o, alpha, ceiling);
      EXPECT_NEAR(f.a(), 1.0, 1e-6) << "alpha " << alpha << " theta_o " << deg;
      EXPECT_LE(f.total, 1.0 + 1e-6);
      if (alpha <= 1e-4 && deg <= 70) EXPECT_NEAR(f.total, 1.0, 1e-6) << deg;
    }
}

// alpha = 1e-4: A is the mirror ray's indicator (reflectAt() finds the panel) wherever the
// mirror direction is > 0.01 rad from the panel's outline, i.e. where the GGX tail beyond the
// outline, ~(2 alpha / 0.01)^2 = 4e-4, is negligible.
TEST(GlossyTruth, TinyRoughnessIsMirrorIndicator) {
  const Scene scene = makeGlossyScene(0.01);
  const ssrcl::Camera camera = makeCamera(scene.view, kWidth, kHeight);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const Primitive& panel = scene.primitives[kGlossyPanel];
  const double delta = 0.01;
  std::size_t clear = 0, hits = 0, floor = 0;
  for (int y = 0; y < kHeight; y += 2)
    for (int x = y % 4; x < kWidth; x += 4) {
      const Hit& h = g.hit(x, y);
      if (h.primitive != kGlossyFloor) continue;
      ++floor;
      const dvec3 view = primaryRay(camera, x + 0.5, y + 0.5).direction;
      const MirrorSample s = reflectAt(scene, camera, h, view);
      const bool found = s.hit.primitive == kGlossyPanel;
      // Clear of the outline: the mirror direction tilted by delta four ways agrees.
      dvec3 u, v;
      planeAxes(s.reflected.direction, u, v);
      bool agree = true;
      for (const dvec3& t : {u, -u, v, -v}) {
        const Ray tilted{h.position, glm::normalize(s.reflected.direction + delta * t)};
        agree = agree && (intersect(scene, tilted, 1e-9).primitive == kGlossyPanel) == found;
      }
      if (!agree) continue;
      ++clear;
      hits += found;
      const double a = lobeFraction(h.position, h.normal, -view, 1e-4, panel).a();
      ASSERT_NEAR(a, found ? 1.0 : 0.0, 1e-3) << pixelName(x, y);
    }
  // Most pixels are clear of the outline, and both outcomes occur.
  EXPECT_GT(clear, floor * 8 / 10);
  EXPECT_GT(hits, clear / 5);
  EXPECT_LT(hits, clear * 4 / 5);
}

// Convergence at floor pixels spread across the transition from missing to finding the panel:
// refining every quadrature parameter (twice the Gauss points and phi panels, psi pieces down to
// 1/4 the width, 1/100 of the tolerance) moves A by < 1e-5 (asked: 1e-4); brute-force ray casting
// against the scene, an independent method, approaches it as ~1 / grid.
TEST(GlossyTruth, ConvergedAndAgreesWithRayCasting) {
  for (double r : {0.15, 0.3, 0.6}) {
    const Scene scene = makeGlossyScene(r);
    const ssrcl::Camera camera = makeCamera(scene.view, kWidth, kHeight);
    const Primitive& panel = scene.primitives[kGlossyPanel];
    double worstRefined = 0, worstBrute[2] = {0, 0};
    for (int y = kHeight - 1; y >= 54; y -= 7) {
      const int x = kWidth / 2 + (y % 3 - 1) * 30;
      const Hit hit = intersect(scene, primaryRay(camera, x + 0.5, y + 0.5));
      ASSERT_EQ(hit.primitive, kGlossyFloor) << pixelName(x, y);
      const dvec3 o = -primaryRay(camera, x + 0.5, y + 0.5).direction;
      const LobeFraction t = lobeFraction(hit.position, hit.normal, o, r * r, panel);
      const LobeFraction fine = lobeFraction(hit.position, hit.normal, o, r * r, panel, Quadrature{}.refined());
      worstRefined = std::max(worstRefined, std::abs(fine.a() - t.a()));
      std::ostringstream line;
      line << "r " << r << " pixel " << pixelName(x, y) << " A " << t.a() << " lobe total " << t.total
           << "; refined - A " << fine.a() - t.a() << "; brute force - A";
      const int grids[2] = {256, 1024};
      for (int k = 0; k < 2; ++k) {
        const LobeFraction b =
            lobeFractionBruteForce(scene, kGlossyPanel, hit.position, hit.normal, o, r * r, grids[k]);
        worstBrute[k] = std::max(worstBrute[k], std::abs(b.a() - t.a()));
        line << " " << grids[k] << "^2: " << b.a() - t.a();
      }
      std::cout << line.str() << "\n";
    }
    std::cout << "r " << r << " worst |refined - A| " << worstRefined << ", |brute force - A| 256^2 " << worstBrute[0]
              << " 1024^2 " << worstBrute[1] << "\n";
    EXPECT_LT(worstRefined, 1e-5);
    // Measured worst 1e-4 at 1024^2 (4e-4 at 256^2): the ray-cast V is a step function.
    EXPECT_LT(worstBrute[1], 3e-4);
  }
}

// The scene is as makeGlossyScene() promises, at the test's resolution.
TEST(GlossyTruth, SceneIsAsDesigned) {
  const GlossyCase& c = glossyCase(0.3);
  const Primitive& panel = c.scene.primitives[kGlossyPanel];
  const double top = panel.center.y + panel.halfSize.x;
  // Fully on screen with a margin, top edge on the boundary above row 16, the eye above it.
  for (double sx : {-1.0, 1.0})
    for (double y : {0.0, top}) {
      const dvec3 s = projectToScreen(c.camera, dvec3(sx * panel.halfSize.z, y, panel.center.z));
      EXPECT_GT(s.x, 10);
      EXPECT_LT(s.x, kWidth - 10);
      EXPECT_GT(s.y, 10);
      EXPECT_LT(s.y, kHeight - 10);
    }
  EXPECT_NEAR(projectToScreen(c.camera, dvec3(0, top, panel.center.z)).y, 16.0, 1e-9);
  EXPECT_GT(c.scene.view.eye.y, top);
  std::size_t floor = 0, onPanel = 0, sky = 0;
  double aMin = 1, aMax = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Hit& h = c.g.hit(x, y);
      sky += !h;
      onPanel += h.primitive == kGlossyPanel;
      if (h.primitive != kGlossyFloor) continue;
      ++floor;
      EXPECT_GT(h.position.z, panel.center.z);  // in front: its rays can only reach the front face
      EXPECT_LT(std::abs(h.position.x), panel.halfSize.z);
      aMin = std::min(aMin, c.truth.at(x, y).a);
      aMax = std::max(aMax, c.truth.at(x, y).a);
    }
  std::cout << "floor " << floor << " panel " << onPanel << " sky " << sky << " pixels; A_true in [" << aMin << ", "
            << aMax << "]\n";
  EXPECT_GT(floor, 5000u);
  EXPECT_GT(onPanel, 2500u);
  EXPECT_GT(sky, 2500u);
  EXPECT_LT(aMin, 0.05);
  EXPECT_GT(aMax, 0.95);
}

// ---------------------------------------------------------------------------------------------
// The SSR pipeline against the truth.

// `g` replaces the case's G-buffer (same surfaces, other pass values).
ssrcl::Image runSsr(const GlossyCase& c, ssrcl::TraceSettings s, const ssrcl::GBuffer* g = nullptr) {
  static ssrcl::Device device = testDevice();  // one device: kernels compile once per process
  s.edgeFade = 0;                              // the truth has no fade
  s.maxRoughness = kMaxRoughness;
  ssrcl::Pipeline p(device);
  p.setGBuffer(g ? *g : c.g);
  p.setCamera(c.camera);
  p.settings() = s;
  p.commit();
  p.execute();
  return p.output("reflection");
}

ssrcl::TraceSettings reference(int spp) {
  ssrcl::TraceSettings s = ssrcl::qualityPreset("reference");
  s.samplesPerPixel = spp;
  return s;
}

// Over floor pixels: A - A_true, and rgb - rgb_true pooled over the three channels.
struct Errors {
  double biasA = 0, meanAbsA = 0, rmsA = 0, biasRgb = 0, meanAbsRgb = 0, rmsRgb = 0;
  dvec3 biasChannel{0.0};
  std::size_t pixels = 0;
};

// `lo`/`hi` given: the error is the distance outside [lo, hi] (scaled by the panel's radiance for
// rgb) instead of the difference to the truth. `only` given: over the pixels (x, y) it accepts.
Errors compare(const GlossyCase& c, const ssrcl::Image& out, const GlossyTruth* lo = nullptr,
               const GlossyTruth* hi = nullptr, const std::function<bool(int, int)>& only = {}) {
  const dvec3 radiance = glossyPanelRadiance();
  const auto error = [&](double got, std::size_t i, double scale) {
    if (!lo) return got - scale * c.truth.pixels[i].a;
    const double l = scale * lo->pixels[i].a, h = scale * hi->pixels[i].a;
    return got > h ? got - h : got < l ? got - l : 0.0;
  };
  Errors e;
  for (std::size_t i = 0; i < c.truth.pixels.size(); ++i) {
    if (!c.truth.pixels[i].receiver || (only && !only(int(i % kWidth), int(i / kWidth)))) continue;
    ++e.pixels;
    const double da = error(out.data[4 * i + 3], i, 1.0);
    e.biasA += da;
    e.meanAbsA += std::abs(da);
    e.rmsA += da * da;
    for (int ch = 0; ch < 3; ++ch) {
      const double d = error(out.data[4 * i + std::size_t(ch)], i, radiance[ch]);
      e.biasRgb += d / 3;
      e.biasChannel[ch] += d;
      e.meanAbsRgb += std::abs(d) / 3;
      e.rmsRgb += d * d / 3;
    }
  }
  const double n = double(std::max<std::size_t>(e.pixels, 1));
  e.biasA /= n;
  e.meanAbsA /= n;
  e.rmsA = std::sqrt(e.rmsA / n);
  e.biasRgb /= n;
  e.biasChannel /= n;
  e.meanAbsRgb /= n;
  e.rmsRgb = std::sqrt(e.rmsRgb / n);
  return e;
}

std::string describe(const Errors& e) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "A bias %+.5f mean|err| %.5f rms %.5f; rgb bias %+.5f (%+.5f %+.5f %+.5f) mean|err| %.5f rms %.5f",
                e.biasA, e.meanAbsA, e.rmsA, e.biasRgb, e.biasChannel.r, e.biasChannel.g, e.biasChannel.b, e.meanAbsRgb,
                e.rmsRgb);
  return buf;
}

void record(const std::string& prefix, const Errors& e) {
  const auto put = [&](const char* key, double v) {
    ::testing::Test::RecordProperty(prefix + "_" + key, std::to_string(v));
  };
  put("bias_a", e.biasA);
  put("mean_abs_a", e.meanAbsA);
  put("rms_a", e.rmsA);
  put("bias_rgb", e.biasRgb);
  put("bias_r", e.biasChannel.r);
  put("bias_g", e.biasChannel.g);
  put("bias_b", e.biasChannel.b);
  put("mean_abs_rgb", e.meanAbsRgb);
  put("rms_rgb", e.rmsRgb);
}

// Finite, A in [0, 1]; sky pixels and pixels above maxRoughness (the panel) exactly 0.
void checkInvariants(const GlossyCase& c, const ssrcl::Image& out) {
  ASSERT_EQ(out.width, kWidth);
  ASSERT_EQ(out.height, kHeight);
  ASSERT_EQ(out.channels, 4);
  std::size_t sky = 0, rough = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      for (int ch = 0; ch < 4; ++ch) ASSERT_TRUE(std::isfinite(out.at(x, y, ch))) << pixelName(x, y);
      ASSERT_GE(out.at(x, y, 3), 0.0f) << pixelName(x, y);
      ASSERT_LE(out.at(x, y, 3), 1.0f) << pixelName(x, y);
      const int prim = c.g.hit(x, y).primitive;
      const bool tooRough = prim >= 0 && c.g.roughness.at(x, y, 0) > kMaxRoughness;
      sky += prim < 0;
      rough += tooRough;
      if (prim < 0 || tooRough)
        for (int ch = 0; ch < 4; ++ch)
          ASSERT_EQ(out.at(x, y, ch), 0.0f) << pixelName(x, y) << (prim < 0 ? " sky" : " above max roughness");
    }
  ASSERT_GT(sky, 0u);
  ASSERT_GT(rough, 0u);
}

class GlossySsr : public ::testing::TestWithParam<double> {};

// The reference tracer (linear half-pixel march, no reuse, no prefilter) converges to the truth up
// to the panel outline's discretization.
TEST_P(GlossySsr, ReferenceConvergesToTruth) {
  GlossyCase& c = glossyCase(GetParam());
  computeEnvelope(c);
  std::map<int, Errors> vsTruth, vsEnvelope;
  for (int spp : {16, 64, 256}) {
    const ssrcl::Image out = runSsr(c, reference(spp));
    checkInvariants(c, out);
    vsTruth[spp] = compare(c, out);
    vsEnvelope[spp] = compare(c, out, c.shrunk.get(), c.grown.get());
    std::cout << "r " << c.roughness << " reference " << spp << " spp vs truth: " << describe(vsTruth[spp])
              << "\n   outside the half-pixel envelope: " << describe(vsEnvelope[spp]) << "\n";
    record("spp" + std::to_string(spp), vsTruth[spp]);
    record("spp" + std::to_string(spp) + "_outside_envelope", vsEnvelope[spp]);
    if (spp == 256) {
      // The pixels furthest outside the envelope, for diagnosis.
      std::vector<std::pair<double, std::size_t>> worst;
      for (std::size_t i = 0; i < c.truth.pixels.size(); ++i) {
        if (!c.truth.pixels[i].receiver) continue;
        const double a = out.data[4 * i + 3], lo = c.shrunk->pixels[i].a, hi = c.grown->pixels[i].a;
        worst.emplace_back(a > hi ? a - hi : a < lo ? lo - a : 0.0, i);
      }
      std::partial_sort(worst.begin(), worst.begin() + 3, worst.end(), std::greater<>());
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = worst[std::size_t(k)].second;
        const int x = int(i % kWidth), y = int(i / kWidth);
        std::cout << "   " << pixelName(x, y) << " A_true " << c.truth.pixels[i].a << " envelope ["
                  << c.shrunk->pixels[i].a << ", " << c.grown->pixels[i].a << "] got A " << out.at(x, y, 3) << " rgb "
                  << out.at(x, y, 0) << " " << out.at(x, y, 1) << " " << out.at(x, y, 2) << "\n";
      }
    }
  }
  double envelopeWidth = 0;
  for (std::size_t i = 0; i < c.truth.pixels.size(); ++i)
    if (c.truth.pixels[i].receiver) envelopeWidth += c.grown->pixels[i].a - c.shrunk->pixels[i].a;
  envelopeWidth /= double(vsTruth[256].pixels);
  const double ratio = vsTruth[16].rmsA / vsTruth[64].rmsA;
  std::cout << "   rms(16 spp) / rms(64 spp) " << ratio << "; mean envelope width " << envelopeWidth << "\n";
  RecordProperty("rms_ratio_16_64", std::to_string(ratio));
  RecordProperty("envelope_width", std::to_string(envelopeWidth));

  // Sampling error: 4x the rays cut independent Monte Carlo noise 2x; the per-pixel shifted R2
  // sequence does better (~N^-3/4 for an integrand with an edge: 2.8x; N^-1 for a smooth one: 4x),
  // and the discretization floor below pulls the ratio down. Measured 2.8-2.9.
  EXPECT_GE(ratio, 1.7);
  EXPECT_LE(ratio, 3.6);
  // At 64 spp the noise dominates (measured rms 0.016-0.017, mean |err| 0.012-0.013): 1.5x margin.
  EXPECT_LT(vsTruth[64].rmsA, 0.025);
  EXPECT_LT(vsTruth[64].meanAbsA, 0.02);
  EXPECT_LT(vsTruth[64].rmsRgb, 0.025);
  // What remains at 256 spp is the outline: the depth buffer knows the panel per pixel and the
  // march tests it every half pixel, so the silhouette the rays find may sit up to ~half a pixel
  // off the exact one. Measured: bias -0.0028 (r 0.3) and -0.0016 (r 0.6), i.e. the rays find a
  // panel ~0.18 px smaller than the exact one all round (mean envelope width 0.0155 and 0.0090
  // per pixel of outline). Asserted: |bias| within half the envelope's width (the outline within
  // half a pixel on average), and what lies outside the envelope is mostly noise (measured signed
  // -0.0006/-0.0008, the 0.18 px shift; mean |outside| 0.0017/0.0020 for A, 0.0010/0.0011 rgb).
  EXPECT_LT(std::abs(vsTruth[256].biasA), 0.5 * envelopeWidth);
  EXPECT_LT(std::abs(vsEnvelope[256].biasA), 0.0015);
  EXPECT_LT(vsEnvelope[256].meanAbsA, 0.004);
  EXPECT_LT(std::abs(vsEnvelope[256].biasRgb), 0.001);
  EXPECT_LT(vsEnvelope[256].meanAbsRgb, 0.0025);
}

// Over floor pixels that found something (A > 0.05): mean per channel of rgb / A - L, the panel's
// radiance L. Hits carry the exact colour without prefiltering; a prefiltered read near the
// panel's outline mixes in sky and floor.
dvec3 colourOfHits(const GlossyCase& c, const ssrcl::Image& out) {
  dvec3 sum(0.0);
  std::size_t n = 0;
  for (std::size_t i = 0; i < c.truth.pixels.size(); ++i) {
    const double a = out.data[4 * i + 3];
    if (!c.truth.pixels[i].receiver || !(a > 0.05)) continue;
    ++n;
    for (int ch = 0; ch < 3; ++ch) sum[ch] += out.data[4 * i + std::size_t(ch)] / a - glossyPanelRadiance()[ch];
  }
  return sum / double(std::max<std::size_t>(n, 1));
}

// The fast path (medium: Hi-Z, 4 rays, 5x5 ray reuse, prefiltered hits, then the edge-aware
// filter), and its colour. The reuse is checked unfiltered, against the same 4 rays without
// neighbours; the filter, on by default, must then lower the error against the truth further
// without adding bias.
TEST_P(GlossySsr, FastPathBiasAndError) {
  const GlossyCase& c = glossyCase(GetParam());
  ssrcl::TraceSettings unfiltered;
  unfiltered.denoise = false;
  const ssrcl::Image medium = runSsr(c, unfiltered);
  checkInvariants(c, medium);
  const ssrcl::Image filtered = runSsr(c, ssrcl::TraceSettings{});
  checkInvariants(c, filtered);
  ssrcl::TraceSettings own = unfiltered;  // the same 4 rays, no reuse
  own.reuseRadius = 0;
  const ssrcl::Image noReuse = runSsr(c, own);
  checkInvariants(c, noReuse);
  own.samplesPerPixel = 1;
  const ssrcl::Image one = runSsr(c, own);
  checkInvariants(c, one);
  const Errors e = compare(c, medium), e4 = compare(c, noReuse), e1 = compare(c, one), ef = compare(c, filtered);
  ssrcl::TraceSettings exact = reference(64);
  exact.prefilter = false;
  const dvec3 tint = colourOfHits(c, medium), tintRef = colourOfHits(c, runSsr(c, exact));
  std::cout << "r " << c.roughness << " medium unfiltered: " << describe(e) << "\n   filtered: " << describe(ef)
            << "\n   4 spp, no reuse: " << describe(e4)
            << "\n   1 spp, no reuse: " << describe(e1) << "\n   rgb / A - L: prefiltered " << tint.r << " " << tint.g
            << " " << tint.b << ", reference 64 spp " << tintRef.r << " " << tintRef.g << " " << tintRef.b << "\n";
  record("medium_unfiltered", e);
  record("medium", ef);
  record("no_reuse_4spp", e4);
  record("no_reuse_1spp", e1);
  for (int ch = 0; ch < 3; ++ch) RecordProperty("medium_tint_" + std::to_string(ch), std::to_string(tint[ch]));
  // Measured (5x5 reuse, PoCL, issue 17): bias A -0.0022 (r 0.3) and -0.0016 (r 0.6), per
  // channel |bias rgb| <= 0.0020, rms A 0.031-0.038, rms rgb 0.020-0.024. Bounds at those values
  // plus a margin: the seed is fixed, so what moves them is float rounding of hit decisions on
  // another platform (a few pixels of ~5600): 0.004 for the biases, 10% on the rms. A GGX pdf
  // evaluated at 1.05 alpha (bias A +0.0054 at r 0.6) or rays reused with the wrong weight
  // exceed them (scripts/mutation-check.sh).
  EXPECT_LT(std::abs(e.biasA), 0.004);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(e.biasChannel[ch]), 0.004) << ch;
  EXPECT_LT(e.rmsA, 0.042);
  EXPECT_LT(e.rmsRgb, 0.027);
  // Reuse pays: the same 4 rays without neighbours are ~2.7x noisier, 1 ray ~7x.
  EXPECT_LT(e.rmsA, 0.6 * e4.rmsA);
  EXPECT_LT(e.rmsRgb, 0.6 * e4.rmsRgb);
  EXPECT_LT(e.rmsA, 0.3 * e1.rmsA);
  // The filter (default) lowers the error against the truth, within the same bias bounds.
  // Measured: rms A 0.032 -> 0.029 (r 0.3) and 0.039 -> 0.029 (r 0.6), bias A -0.0031 / -0.0013.
  EXPECT_LT(ef.rmsA, e.rmsA);
  EXPECT_LT(ef.rmsRgb, e.rmsRgb);
  EXPECT_LT(std::abs(ef.biasA), 0.004);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(ef.biasChannel[ch]), 0.004) << ch;
  // Prefiltered hits must keep the hit surface's colour: the colour pyramid weights texels by
  // surface coverage so the sky beside the panel does not bleed in (before that weighting: up to
  // (-0.027, +0.006, +0.043) at r 0.6; with it: at most 0.006). Bound 0.012. Full-resolution hits
  // read the exact colour.
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_LT(std::abs(tint[ch]), 0.012) << ch;
    EXPECT_LT(std::abs(tintRef[ch]), 1e-4) << ch;
  }
}

// Ray counts that follow roughness (full rays only at roughness 1: 2 rays at r 0.3, 3 at r 0.6)
// change how many rays each pixel draws, so the weights the resolve gives its neighbours' rays;
// the estimate must stay unbiased, its noise between the uniform counts'.
TEST_P(GlossySsr, RaysFollowingRoughnessStayUnbiased) {
  const GlossyCase& c = glossyCase(GetParam());
  ssrcl::TraceSettings s;
  s.fullRaysRoughness = 1.0f;
  const ssrcl::Image adaptive = runSsr(c, s);
  checkInvariants(c, adaptive);
  s.fullRaysRoughness = 0.0f;
  s.samplesPerPixel = 1;
  const Errors e = compare(c, adaptive), e1 = compare(c, runSsr(c, s)), e4 = compare(c, runSsr(c, {}));
  std::cout << "r " << c.roughness << " rays follow roughness: " << describe(e) << "\n";
  record("adaptive", e);
  // Measured bias A -0.0030 (r 0.6), channels within 0.0027; bounds as for the fast path.
  EXPECT_LT(std::abs(e.biasA), 0.004);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(e.biasChannel[ch]), 0.004) << ch;
  EXPECT_LT(e.rmsA, e1.rmsA);
  EXPECT_GT(e.rmsA, e4.rmsA);
}

// The non-default paths against the same truth (issue 17). Bounds: measured (PoCL) plus the fast
// path's margins (0.004 on biases, 10% on rms: fixed seed, only float rounding of hit decisions
// moves them on another platform).

// "high" (16 rays and the edge-aware filter; the resolve takes a quarter of each neighbour's
// rays, host/pipeline/stage_support.hpp resolveRayStride): the filter must cut the error against the truth
// (not only smooth), without biasing it, below the unfiltered resolve of all the rays.
TEST_P(GlossySsr, HighPresetFilterCutsTheErrorWithoutBias) {
  const GlossyCase& c = glossyCase(GetParam());
  ssrcl::TraceSettings high = ssrcl::qualityPreset("high");
  const ssrcl::Image filtered = runSsr(c, high);
  checkInvariants(c, filtered);
  high.denoise = false;
  const Errors e = compare(c, filtered), raw = compare(c, runSsr(c, high));
  std::cout << "r " << c.roughness << " high: " << describe(e) << "\n   unfiltered: " << describe(raw) << "\n";
  record("high", e);
  record("high_unfiltered", raw);
  // Measured: bias A -0.0013 (r 0.3) and -0.0018 (r 0.6), channels within 0.0017; rms A 0.0116
  // and 0.0170 against the unfiltered pass of all rays' 0.0157 and 0.0198 (x0.74, x0.86), mean
  // |err| 0.0079 and 0.0089 against 0.0094 and 0.0110 (x0.84, x0.81). (The filter that compared
  // depths, not planes: rms 0.0127 and 0.0150; the plane test lets a slanted floor's rows in,
  // which gains on both Cycles corpora but costs this r 0.6 floor 1.13x.) A filter that passes
  // its input through leaves the quarter of the taps' noise, above the unfiltered pass of all of
  // them: it fails the rms gain.
  EXPECT_LT(std::abs(e.biasA), 0.004);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(e.biasChannel[ch]), 0.004) << ch;
  EXPECT_LT(e.rmsA, 0.0187);
  EXPECT_LT(e.rmsA, 0.9 * raw.rmsA);
  EXPECT_LT(e.meanAbsA, raw.meanAbsA);
  EXPECT_LT(e.meanAbsRgb, raw.meanAbsRgb);
}

// "draft" (2 rays in one pixel of each 2x2 block, 64 iterations): the three pixels of a block
// without rays of their own are reconstructed from their neighbours' rays; against the truth they
// must be about as good as the traced ones, and the whole pass unbiased.
TEST_P(GlossySsr, DraftStrideTwoReconstructsTheUntracedPixels) {
  const GlossyCase& c = glossyCase(GetParam());
  const ssrcl::Image draft = runSsr(c, ssrcl::qualityPreset("draft"));
  checkInvariants(c, draft);
  const auto traced = [](int x, int y) { return x % 2 == 0 && y % 2 == 0; };
  const Errors e = compare(c, draft), own = compare(c, draft, nullptr, nullptr, traced),
               borrowed = compare(c, draft, nullptr, nullptr, [&](int x, int y) { return !traced(x, y); });
  std::cout << "r " << c.roughness << " draft: " << describe(e) << "\n   traced pixels: " << describe(own)
            << "\n   reconstructed pixels: " << describe(borrowed) << "\n";
  record("draft", e);
  record("draft_reconstructed", borrowed);
  // Measured: bias A -0.0026 (r 0.3) and -0.0001 (r 0.6), reconstructed pixels -0.0024 and
  // -0.0002, channels within 0.0023; rms A 0.045 and 0.056, the reconstructed pixels' 0.97x and
  // 1.09x the traced ones' (the filter's radius follows the rays a pixel has, a reconstructed
  // pixel counting as one: before, with one radius for all, 0.088 and 0.116, 1.22x and 1.30x).
  // Bounds: biases 0.002 beyond the worst (as the fast path's margin), rms 10%. Untraced pixels
  // left empty fail the bias at once; a radius undefined for them, the ratio (1.85x).
  EXPECT_LT(std::abs(e.biasA), 0.0046);
  EXPECT_LT(std::abs(borrowed.biasA), 0.0046);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(borrowed.biasChannel[ch]), 0.0046) << ch;
  EXPECT_LT(e.rmsA, 0.062);
  EXPECT_LT(borrowed.rmsA, 1.2 * own.rmsA);
}

// The filter in two passes, along y then x (draft's, TraceSettings::separableDenoise), against the
// square of taps over the same rays and against no filter: it must cut the error against the
// truth about as the square does, without bias.
TEST_P(GlossySsr, SeparableFilterCutsTheErrorAsTheSquareDoes) {
  const GlossyCase& c = glossyCase(GetParam());
  for (const char* preset : {"draft", "medium"}) {
    ssrcl::TraceSettings s = ssrcl::qualityPreset(preset);
    s.separableDenoise = true;
    const ssrcl::Image separable = runSsr(c, s);
    checkInvariants(c, separable);
    s.separableDenoise = false;
    const Errors e = compare(c, separable), square = compare(c, runSsr(c, s));
    s.denoise = false;
    const Errors raw = compare(c, runSsr(c, s));
    std::cout << "r " << c.roughness << " " << preset << " separable: " << describe(e)
              << "\n   square: " << describe(square) << "\n   unfiltered: " << describe(raw) << "\n";
    record(std::string(preset) + "_separable", e);
    // Measured: rms A 1.015x / 0.999x the square's (draft, r 0.3 / 0.6) and 1.026x / 0.983x
    // (medium), 0.36x / 0.35x and 0.68x / 0.61x the unfiltered pass's; bias A within 0.0029.
    // Bounds: rms 1.06x the square's, 0.75x the unfiltered; biases as the fast path's. A second
    // pass that takes no taps (one axis filtered) leaves 2.1x / 2.4x the square's rms at draft.
    EXPECT_LT(e.rmsA, 1.06 * square.rmsA) << preset;
    EXPECT_LT(e.rmsRgb, 1.06 * square.rmsRgb) << preset;
    EXPECT_LT(e.rmsA, 0.75 * raw.rmsA) << preset;
    EXPECT_LT(std::abs(e.biasA), 0.004) << preset;
    for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(e.biasChannel[ch]), 0.004) << preset << " " << ch;
  }
}

// --roughness-mapping linear: alpha is the roughness pass itself. Given roughness^2 it must
// reproduce the squared mapping's truth (alpha = roughness^2) within the fast path's bounds.
TEST_P(GlossySsr, LinearRoughnessMappingTakesThePassAsAlpha) {
  const GlossyCase& c = glossyCase(GetParam());
  ssrcl::GBuffer alphaPass = c.g;
  for (float& r : alphaPass.roughness.data) r *= r;
  ssrcl::TraceSettings s;
  s.roughnessMapping = ssrcl::RoughnessMapping::Linear;
  const ssrcl::Image out = runSsr(c, s, &alphaPass);
  checkInvariants(c, out);
  const Errors e = compare(c, out);
  std::cout << "r " << c.roughness << " linear mapping of roughness^2: " << describe(e) << "\n";
  record("linear_mapping", e);
  // Measured: the squared mapping's numbers to the last digit (bias A -0.0022 / -0.0016, rms A
  // 0.031 / 0.038); its bounds.
  EXPECT_LT(std::abs(e.biasA), 0.004);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LT(std::abs(e.biasChannel[ch]), 0.004) << ch;
  EXPECT_LT(e.rmsA, 0.042);
  EXPECT_LT(e.rmsRgb, 0.027);
}

INSTANTIATE_TEST_SUITE_P(Roughness, GlossySsr, ::testing::Values(0.3, 0.6),
                         [](const auto& info) { return "r" + std::to_string(int(std::lround(info.param * 100))); });

// A creased floor: a ridge along x = 0 with the halves' normals 30 degrees apart (dot 0.87, below
// the resolve's 0.9), roughness 0.6 so that the halves' lobes overlap. Pixels within the reuse
// radius of the crease must not take the other half's rays: those were drawn from another lobe,
// which covers only part of this pixel's hemisphere, so the ratio estimate loses what only its
// own lobe sees. Against the truth of both halves, over those pixels.
TEST(GlossySsrCrease, RaysAreNotReusedAcrossTheCrease) {
  GlossyCase c;
  c.roughness = 0.6;
  c.scene = makeCreasedGlossyScene(c.roughness, 15.0);
  c.camera = makeCamera(c.scene.view, kWidth, kHeight);
  c.g = renderGBuffer(c.scene, c.camera);
  c.truth = glossyTruth(c.scene, c.camera, c.g, kGlossyFloor, kGlossyPanel);
  const GlossyTruth right = glossyTruth(c.scene, c.camera, c.g, kCreaseRightHalf, kGlossyPanel);
  for (std::size_t i = 0; i < right.pixels.size(); ++i)
    if (right.pixels[i].receiver) c.truth.pixels[i] = right.pixels[i];
  const int reach = ssrcl::TraceSettings{}.reuseRadius;
  const auto nearCrease = [&](int x, int y) {
    const int own = c.g.hit(x, y).primitive;
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dx = -reach; dx <= reach; ++dx) {
        const int qx = x + dx, qy = y + dy;
        if (qx < 0 || qy < 0 || qx >= kWidth || qy >= kHeight) continue;
        const int other = c.g.hit(qx, qy).primitive;
        if (other != own && (other == kGlossyFloor || other == kCreaseRightHalf)) return true;
      }
    return false;
  };
  // Over four seeds: one seed's band moves its bias by +-0.006 and its rms by +-0.006, as much as
  // the mutant does.
  double bias = 0.0, rms = 0.0;
  constexpr int kSeeds = 4;
  for (int seed = 0; seed < kSeeds; ++seed) {
    ssrcl::TraceSettings s;
    s.seed = seed;
    const ssrcl::Image out = runSsr(c, s);
    const Errors band = compare(c, out, nullptr, nullptr, nearCrease), all = compare(c, out);
    std::cout << "creased floor, medium, seed " << seed << ": " << describe(all) << "\n   within " << reach
              << " px of the crease: " << describe(band) << "\n";
    ASSERT_GT(band.pixels, 100u);
    bias += band.biasA / kSeeds;
    rms += band.rmsA / kSeeds;
  }
  RecordProperty("crease_band_bias", std::to_string(bias));
  RecordProperty("crease_band_rms", std::to_string(rms));
  // Measured (PoCL), the mean of seeds 0-3: in the band bias A +0.0118, rms A 0.0526 (over the
  // whole floor +0.0099, 0.053: the tilted halves' own residue, not understood yet; the filter's
  // kernel, cut at the crease, leans on each half's interior); reusing the other half's rays moves
  // the band's bias to +0.0034 (seeds 0-3: -0.016, -0.003, -0.006, -0.006 each), its rms nowhere.
  // Bounds: the bias within 0.004 of the measured value, the rms 10% above it.
  EXPECT_LT(std::abs(bias - 0.0118), 0.004);
  EXPECT_LT(rms, 0.058);
}

// Same inputs and seed: bit-identical output; another seed: another output.
TEST(GlossySsrDeterminism, SeedDecidesTheOutput) {
  const GlossyCase& c = glossyCase(0.3);
  for (ssrcl::TraceSettings s : {reference(16), ssrcl::TraceSettings{}}) {
    s.seed = 7;
    const ssrcl::Image a = runSsr(c, s), b = runSsr(c, s);
    s.seed = 8;
    const ssrcl::Image other = runSsr(c, s);
    EXPECT_EQ(a.data, b.data);
    EXPECT_NE(a.data, other.data);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.data.size(); i += 4) differ += a.data[i + 3] != other.data[i + 3];
    EXPECT_GT(differ, 1000u);  // most glossy floor pixels, not a stray one
  }
}

}  // namespace
