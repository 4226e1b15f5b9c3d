// ssrcl::temporalBlend against an analytic shot: a glossy floor (y = 0) under a textured ceiling
// (y = H), a camera trucking sideways. Each frame's "pass" is the ceiling's exact colour where the
// floor pixel's mirror ray meets it, plus independent noise; its hit distance is exact. Blending
// must find each neighbour where it reflects the same ceiling point (the reflected point), so
// the blend's error against the exact colour falls as the noise averages; it must refuse
// neighbours whose hit distances disagree by more than the lobe's roughness spreads them, and
// leave mirror pixels and misses alone, and refuse neighbours lit otherwise (a light switched on
// mid-shot).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <optional>

#include "ssrcl/error.hpp"
#include "ssrcl/temporal.hpp"
#include "support/simple_camera.hpp"

namespace {

constexpr int kW = 96, kH = 64;
constexpr double kCeiling = 2.0;

double texture(double x, double z) { return 0.5 + 0.25 * std::sin(1.3 * x) * std::cos(0.9 * z); }

// Deterministic noise in [-0.5, 0.5) per frame and pixel.
double noise(int frame, int pixel, int channel) {
  uint32_t h = uint32_t(frame) * 0x9e3779b9u ^ uint32_t(pixel) * 0x85ebca6bu ^ uint32_t(channel) * 0xc2b2ae35u;
  h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
  return double(h) / 4294967296.0 - 0.5;
}

struct AnalyticFrame {
  ssrcl::Image reflection{kW, kH, 4}, distance{kW, kH, 1}, depth{kW, kH, 1}, normal{kW, kH, 3}, roughness{kW, kH, 1};
  ssrcl::Image truth{kW, kH, 1};  // the ceiling's colour each floor pixel reflects
  ssrcl::Camera camera;
};

// Frame `f` of the truck: the camera 0.15 units along x a frame; `ceiling`: where its hits are;
// `light`: the ceiling's brightness.
AnalyticFrame makeFrame(int f, double noiseAmplitude, double ceiling = kCeiling, float roughness = 0.3f,
                        double light = 1.0) {
  AnalyticFrame a;
  const glm::dvec3 eye(0.15 * f, 1.0, 4.0);
  a.camera = ssrcl::test::perspectiveCamera(kW, kH, eye, eye + glm::dvec3(0, -0.6, -1), 60.0);
  const glm::dmat4 inverseProjection = glm::inverse(a.camera.projection), inverseView = glm::inverse(a.camera.view);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::dvec3 c = ssrcl::cameraPointAt(inverseProjection, a.camera, x + 0.5, y + 0.5, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(inverseView * glm::dvec4(c, 0.0)));
      a.depth.at(x, y, 0) = 1e10f;  // sky unless the ray meets the floor
      if (dir.y >= -1e-3) continue;
      const glm::dvec3 p = eye + dir * (-eye.y / dir.y);
      a.depth.at(x, y, 0) = float(-(a.camera.view * glm::dvec4(p, 1.0)).z);
      a.normal.at(x, y, 1) = 1.0f;
      a.roughness.at(x, y, 0) = roughness;
      const glm::dvec3 r(dir.x, -dir.y, dir.z);
      const double d = ceiling / r.y;
      const glm::dvec3 hit = p + r * d;
      a.distance.at(x, y, 0) = float(d);
      a.truth.at(x, y, 0) = float(light * texture(hit.x, hit.z));
      for (int ch = 0; ch < 3; ++ch)
        a.reflection.at(x, y, ch) = float(a.truth.at(x, y, 0) + noiseAmplitude * noise(f, y * kW + x, ch));
      a.reflection.at(x, y, 3) = 1.0f;
    }
  return a;
}

std::vector<ssrcl::TemporalFrame> window(const std::vector<AnalyticFrame>& frames) {
  std::vector<ssrcl::TemporalFrame> out;
  for (const AnalyticFrame& a : frames)
    out.push_back({&a.reflection, &a.distance, &a.depth, &a.normal, &a.roughness, a.camera, nullptr});
  return out;
}

// RMS of the pass's colour against the truth over the floor pixels the camera sees.
double rmsError(const ssrcl::Image& pass, const AnalyticFrame& a) {
  double se = 0;
  size_t n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (a.depth.at(x, y, 0) < 1e9f)
        for (int c = 0; c < 3; ++c, ++n) se += std::pow(pass.at(x, y, c) - a.truth.at(x, y, 0), 2);
  return std::sqrt(se / double(n));
}

TEST(TemporalBlend, AveragesNoiseAtTheReflectedPoint) {
  std::vector<AnalyticFrame> frames;
  for (int f = -3; f <= 3; ++f) frames.push_back(makeFrame(f, 0.2));
  const ssrcl::Image blended = ssrcl::temporalBlend(window(frames), 3, {});
  const double own = rmsError(frames[3].reflection, frames[3]), blend = rmsError(blended, frames[3]);
  std::cout << "RMS error against the exact ceiling: own " << own << ", blended over 7 frames " << blend << "\n";
  // 7 frames of independent noise: sqrt(7) = 2.6 less where all are found (fewer at the edges).
  EXPECT_LT(blend, own / 2.0);
  // Noise-free frames: the blend reads the same ceiling point in every neighbour, so it only adds
  // bilinear interpolation error, a small part of what the same pixels of the neighbours (no
  // reprojection: each shows another ceiling point) are off.
  // The shot's first frame: its neighbours all to one side, where the first-order shifts of a
  // symmetric window would cancel.
  std::vector<AnalyticFrame> clean;
  for (int f = 0; f <= 6; ++f) clean.push_back(makeFrame(f, 0.0));
  ssrcl::Image samePixel(kW, kH, 4);
  for (const AnalyticFrame& a : clean)
    for (size_t v = 0; v < samePixel.data.size(); ++v) samePixel.data[v] += a.reflection.data[v] / float(clean.size());
  const double reprojected = rmsError(ssrcl::temporalBlend(window(clean), 0, {}), clean[0]);
  const double unmoved = rmsError(samePixel, clean[0]);
  std::cout << "noise-free: blended " << reprojected << ", same pixels averaged " << unmoved << "\n";
  EXPECT_LT(reprojected, 0.01);
  EXPECT_LT(reprojected, unmoved / 5);
}

// Frames weigh 1 - d / (R + 1) by their distance d from the centre, R the window's longer side:
// four takes of one frame (one camera, so every tap lands on its own pixel whole), each a constant
// colour, the centre second (R = 2): 1, 2/3, 2/3 and 1/3 where the rays hit; the left quarter's
// rays miss (distance 0) and keep the centre's take.
TEST(TemporalBlend, FramesWeighLessTheFartherTheyAre) {
  const float colour[4] = {1.0f, 1.2f, 1.4f, 1.6f};
  std::vector<AnalyticFrame> frames(4, makeFrame(0, 0.0));
  for (int j = 0; j < 4; ++j)
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        for (int ch = 0; ch < 3; ++ch) frames[j].reflection.at(x, y, ch) = colour[j];
        if (x < kW / 4) frames[j].distance.at(x, y, 0) = 0.0f;
      }
  const ssrcl::Image blended = ssrcl::temporalBlend(window(frames), 1, {});
  const double expected =
      (colour[1] + 2.0 / 3 * colour[0] + 2.0 / 3 * colour[2] + 1.0 / 3 * colour[3]) / (1.0 + 5.0 / 3);
  int hits = 0, misses = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const bool hit = frames[1].distance.at(x, y, 0) > 0.0f;
      (hit ? hits : misses)++;
      EXPECT_NEAR(blended.at(x, y, 0), hit ? expected : colour[1], 1e-5) << x << "," << y;
    }
  EXPECT_GT(hits, kW * kH / 4);
  EXPECT_GT(misses, 0);
}

TEST(TemporalBlend, RefusesNeighboursWhoseHitsDisagree) {
  // Neighbours' hits on a ceiling twice as high: their hit distances are 100% off, more than a
  // lobe of roughness 0.3 spreads them (20% + 2 x 0.3 = 80%), every one refused.
  std::vector<AnalyticFrame> frames;
  for (int f = -2; f <= 2; ++f) frames.push_back(makeFrame(f, 0.2, f == 0 ? kCeiling : 2.0 * kCeiling));
  const ssrcl::Image blended = ssrcl::temporalBlend(window(frames), 2, {});
  EXPECT_EQ(blended.data, frames[2].reflection.data);
}

// A rough lobe's hit distance is a mean over hits spread across it: between views it is off by
// more than a sharp lobe's. 40% off is taken at roughness 0.3 (tolerance 80%) and refused at
// 0.05 (30%), and by the tolerance of a lobe without spread (roughnessSpread 0: 20%).
TEST(TemporalBlend, HitDistanceToleranceWidensWithRoughness) {
  const auto blended = [](float roughness, const ssrcl::TemporalSettings& s) {
    std::vector<AnalyticFrame> frames;
    for (int f = -2; f <= 2; ++f) frames.push_back(makeFrame(f, 0.2, f == 0 ? kCeiling : 1.4 * kCeiling, roughness));
    return ssrcl::temporalBlend(window(frames), 2, s).data != frames[2].reflection.data;
  };
  EXPECT_TRUE(blended(0.3f, {}));
  ssrcl::TemporalSettings noSpread;
  noSpread.roughnessSpread = 0.0f;
  EXPECT_FALSE(blended(0.3f, noSpread));
  EXPECT_FALSE(blended(0.05f, {}));
}

// The ceiling's light switches on at frame 4 of 8 (from 5% of its brightness): geometry agrees
// in every frame, only radiance tells the frames apart. Blended over +-3 frames, each frame must
// keep its own light (no dark history after the switch, no light before it): its error as small
// as the blend of only the frames lit as it is, and under its own noise.
TEST(TemporalBlend, RefusesNeighboursLitOtherwise) {
  constexpr int kSwitch = 4, kFrames = 8, kK = 3;
  std::vector<AnalyticFrame> frames;
  for (int f = 0; f < kFrames; ++f) frames.push_back(makeFrame(f, 0.2, kCeiling, 0.3f, f < kSwitch ? 0.05 : 1.0));
  for (int c = 0; c < kFrames; ++c) {
    const int first = std::max(c < kSwitch ? 0 : kSwitch, c - kK);
    const int last = std::min(c < kSwitch ? kSwitch - 1 : kFrames - 1, c + kK);
    const std::vector<AnalyticFrame> alike(frames.begin() + first, frames.begin() + last + 1);
    const double own = rmsError(frames[c].reflection, frames[c]);
    const double clean = rmsError(ssrcl::temporalBlend(window(alike), size_t(c - first), {}), frames[c]);
    const int from = std::max(0, c - kK), to = std::min(kFrames - 1, c + kK);
    const std::vector<AnalyticFrame> span(frames.begin() + from, frames.begin() + to + 1);
    const double blend = rmsError(ssrcl::temporalBlend(window(span), size_t(c - from), {}), frames[c]);
    std::cout << "frame " << c << ": RMS error own " << own << ", blended " << blend
              << ", blended over the frames lit alike " << clean << "\n";
    // Without the radiance test frames 1-6 take the other light (errors 0.10-0.21); with 3 sigmas
    // (radianceSigmas) instead of 1.5, the upper floor, whose neighbourhoods span much texture,
    // still does (0.05-0.11).
    EXPECT_LT(blend, 1.1 * clean) << "frame " << c;
    EXPECT_LT(blend, 0.75 * own) << "frame " << c;
  }
}

// The ceiling ends at z = kCeilingEnd: beyond it the floor's rays find nothing and the pass holds
// an environment's lookup in the mirror direction of each pixel's own normal, which a normal map
// fixed to the floor ripples (as a wet deck's). That lookup has no noise: each such pixel must
// keep it exactly (its truth, computed here from its own normal), where its neighbours' misses,
// other normals' lookups, would blur the ripples in; the hits must still blend.
TEST(TemporalBlend, MissesKeepTheirEnvironmentLookup) {
  constexpr double kCeilingEnd = -3.0;
  const auto sky = [](const glm::dvec3& d) { return 0.4 + 0.5 * d.y + 0.3 * d.x * d.z; };
  std::vector<AnalyticFrame> frames;
  std::vector<ssrcl::Image> truth;  // each miss pixel's lookup, computed apart from the pass
  size_t misses = 0;
  for (int f = -2; f <= 2; ++f) {
    AnalyticFrame a = makeFrame(f, 0.2);
    ssrcl::Image lookup(kW, kH, 1);
    const glm::dmat4 inverseProjection = glm::inverse(a.camera.projection), inverseView = glm::inverse(a.camera.view);
    const glm::dvec3 eye(inverseView[3]);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (!(a.depth.at(x, y, 0) < 1e9f)) continue;
        const glm::dvec3 c = ssrcl::cameraPointAt(inverseProjection, a.camera, x + 0.5, y + 0.5, a.depth.at(x, y, 0));
        const glm::dvec3 p(inverseView * glm::dvec4(c, 1.0)), view = glm::normalize(p - eye);
        const glm::dvec3 n = glm::normalize(glm::dvec3(0.15 * std::sin(23.0 * p.x), 1.0, 0.15 * std::cos(19.0 * p.z)));
        for (int ch = 0; ch < 3; ++ch) a.normal.at(x, y, ch) = float(n[ch]);
        const glm::dvec3 r(view.x, -view.y, view.z);  // the flat floor's mirror ray meets the ceiling there
        if ((p + r * (kCeiling / r.y)).z > kCeilingEnd) continue;
        lookup.at(x, y, 0) = float(sky(glm::reflect(view, n)));
        for (int ch = 0; ch < 3; ++ch) a.reflection.at(x, y, ch) = lookup.at(x, y, 0);
        a.reflection.at(x, y, 3) = 0.0f;  // none of the lobe found on screen
        a.distance.at(x, y, 0) = 0.0f;
        misses += f == 0;
      }
    frames.push_back(std::move(a));
    truth.push_back(std::move(lookup));
  }
  ASSERT_GT(misses, size_t(kW * kH / 8));
  const ssrcl::Image blended = ssrcl::temporalBlend(window(frames), 2, {});
  double worst = 0;
  size_t hitsBlended = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (!(frames[2].depth.at(x, y, 0) < 1e9f)) continue;
      if (frames[2].distance.at(x, y, 0) > 0.0f) {
        hitsBlended += blended.at(x, y, 0) != frames[2].reflection.at(x, y, 0);
        continue;
      }
      for (int ch = 0; ch < 3; ++ch)
        worst = std::max(worst, double(std::abs(blended.at(x, y, ch) - truth[2].at(x, y, 0))));
    }
  std::cout << "misses " << misses << ", their largest error against their own lookup " << worst << ", hits blended "
            << hitsBlended << "\n";
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(hitsBlended, misses / 2);
}

// A pan: the camera turns 1.5 degrees a frame about its own position over the floor, which
// reflects either a plane y = kFreeHeight that no frame shows (as a rough lobe's hit, a mean
// distance along its centre, that lies on no surface), or a wall z = wallZ that the frames show
// (its own pixels reflect nothing: hit distance 0).
constexpr double kFreeHeight = 0.8;
AnalyticFrame makePanFrame(int f, std::optional<double> wallZ, float roughness = 0.3f) {
  AnalyticFrame a;
  const glm::dvec3 eye(0.0, 1.0, 4.0);
  const double yaw = glm::radians(1.5 * f);
  a.camera = ssrcl::test::perspectiveCamera(kW, kH, eye, eye + glm::dvec3(-std::sin(yaw), -0.3, -std::cos(yaw)), 60.0);
  const glm::dmat4 inverseProjection = glm::inverse(a.camera.projection), inverseView = glm::inverse(a.camera.view);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const glm::dvec3 c = ssrcl::cameraPointAt(inverseProjection, a.camera, x + 0.5, y + 0.5, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(inverseView * glm::dvec4(c, 0.0)));
      const double toFloor = dir.y < -1e-3 ? -eye.y / dir.y : INFINITY;
      const double toWall = wallZ && dir.z < 0.0 ? (*wallZ - eye.z) / dir.z : INFINITY;
      a.depth.at(x, y, 0) = 1e10f;
      if (std::isinf(std::min(toFloor, toWall))) continue;
      const glm::dvec3 p = eye + dir * std::min(toFloor, toWall);
      a.depth.at(x, y, 0) = float(-(a.camera.view * glm::dvec4(p, 1.0)).z);
      a.roughness.at(x, y, 0) = roughness;
      if (toWall < toFloor) {
        a.normal.at(x, y, 2) = 1.0f;
        continue;
      }
      a.normal.at(x, y, 1) = 1.0f;
      const glm::dvec3 r(dir.x, -dir.y, dir.z);
      const double d = wallZ ? (*wallZ - p.z) / r.z : (kFreeHeight - p.y) / r.y;
      const glm::dvec3 hit = p + r * d;
      a.distance.at(x, y, 0) = float(d);
      a.truth.at(x, y, 0) = float(wallZ ? texture(hit.x, 3.0 * hit.y) : texture(hit.x, hit.z));
      for (int ch = 0; ch < 3; ++ch)
        a.reflection.at(x, y, ch) = float(a.truth.at(x, y, 0) + 0.2 * noise(f, y * kW + x, ch));
      a.reflection.at(x, y, 3) = 1.0f;
    }
  return a;
}

// A neighbour that shows a surface behind the hit says the hit's object has moved only where the
// frame itself shows the hit: a hit on no surface stands in front of what every frame shows along
// its line of sight, the frame's own included. Over a pan (each pixel's line of sight the same in
// every frame) the blend must take the neighbours and average the noise out.
TEST(TemporalBlend, AHitOnNoSurfaceIsNotMotion) {
  std::vector<AnalyticFrame> frames;
  for (int f = -2; f <= 2; ++f) frames.push_back(makePanFrame(f, std::nullopt));
  const double own = rmsError(frames[2].reflection, frames[2]);
  const double blend = rmsError(ssrcl::temporalBlend(window(frames), 2, {}), frames[2]);
  std::cout << "RMS error against the exact plane: own " << own << ", blended over 5 frames " << blend << "\n";
  EXPECT_LT(blend, own / 1.8);  // sqrt(5) = 2.2 where all are found
}

// The wall the floor reflects stands 6 units away in frame 0 and 9 in the others (it moved): the
// pixels whose hit frame 0 shows (on the wall there) must keep their own pass, the neighbours
// showing the wall behind it; with the wall still, the same pixels blend. A sharp lobe (roughness
// 0.05) and the widest hit-distance tolerance, so that the motion test, not the distances, refuses.
TEST(TemporalBlend, RefusesAHitThatMoved) {
  const auto blendedShare = [](double otherWall, float movedTolerance) {
    std::vector<AnalyticFrame> frames;
    for (int f = -2; f <= 2; ++f) frames.push_back(makePanFrame(f, f == 0 ? -2.0 : otherWall, 0.05f));
    const AnalyticFrame& a = frames[2];
    ssrcl::TemporalSettings wide;
    wide.distanceTolerance = 0.99f;
    wide.movedTolerance = movedTolerance;
    const ssrcl::Image blended = ssrcl::temporalBlend(window(frames), 2, wide);
    const glm::dmat4 inverseProjection = glm::inverse(a.camera.projection), inverseView = glm::inverse(a.camera.view);
    size_t shown = 0, changed = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (!(a.distance.at(x, y, 0) > 0.0f)) continue;
        // Where its hit lies on screen: the frame shows it there when it is the wall's pixel.
        const glm::dvec3 c = ssrcl::cameraPointAt(inverseProjection, a.camera, x + 0.5, y + 0.5, a.depth.at(x, y, 0));
        const glm::dvec3 p(inverseView * glm::dvec4(c, 1.0)), eye(inverseView[3]);
        const glm::dvec3 v = glm::normalize(p - eye);
        const glm::dvec3 hit = p + glm::dvec3(v.x, -v.y, v.z) * double(a.distance.at(x, y, 0));
        const glm::dvec3 s = ssrcl::cameraToScreen(a.camera, glm::dvec3(a.camera.view * glm::dvec4(hit, 1.0)));
        if (!(s.x >= 0 && s.y >= 0 && s.x < kW && s.y < kH) || a.normal.at(int(s.x), int(s.y), 2) != 1.0f) continue;
        ++shown;
        changed += blended.at(x, y, 0) != a.reflection.at(x, y, 0);
      }
    std::cout << "wall at -2, the others' at " << otherWall << ": " << changed << " of " << shown
              << " pixels whose hit the frame shows blended\n";
    EXPECT_GT(shown, size_t(kW * kH / 20));
    return double(changed) / double(shown);
  };
  EXPECT_LT(blendedShare(-5.0, 0.02f), 0.1);
  EXPECT_GT(blendedShare(-5.0, 0.9f), 0.5);  // the motion test, not the distances, refused them
  EXPECT_GT(blendedShare(-2.0, 0.02f), 0.9);
}

TEST(TemporalBlend, MirrorPixelsKeepTheirOwnPass) {
  std::vector<AnalyticFrame> frames;
  for (int f = -1; f <= 1; ++f) frames.push_back(makeFrame(f, 0.2, kCeiling, 0.01f));
  EXPECT_EQ(ssrcl::temporalBlend(window(frames), 1, {}).data, frames[1].reflection.data);
}

TEST(TemporalBlend, RejectsFramesOfAnotherSize) {
  std::vector<AnalyticFrame> frames;
  for (int f = 0; f < 2; ++f) frames.push_back(makeFrame(f, 0.2));
  frames[1].distance = ssrcl::Image(kW / 2, kH, 1);
  EXPECT_THROW(ssrcl::temporalBlend(window(frames), 0, {}), ssrcl::Error);
  ssrcl::TemporalSettings bad;
  bad.distanceTolerance = 0.0f;
  EXPECT_THROW(ssrcl::temporalBlend(window(frames), 0, bad), ssrcl::Error);
  bad = {};
  bad.roughnessSpread = -1.0f;
  EXPECT_THROW(ssrcl::temporalBlend(window(frames), 0, bad), ssrcl::Error);
  bad = {};
  bad.radianceSigmas = 0.0f;
  EXPECT_THROW(ssrcl::temporalBlend(window(frames), 0, bad), ssrcl::Error);
}

// Statistics computed once per frame and shared by the windows that hold it blend as those
// computed in each blend, bit for bit; another frame's of another size are refused.
TEST(TemporalBlend, SharedFrameStatisticsBlendTheSame) {
  std::vector<AnalyticFrame> frames;
  for (int f = -2; f <= 2; ++f) frames.push_back(makeFrame(f, 0.2, kCeiling, 0.3f));
  std::vector<ssrcl::TemporalFrame> shared = window(frames);
  for (ssrcl::TemporalFrame& f : shared) f.statistics = ssrcl::temporalFrameStatistics(f);
  for (size_t centre = 0; centre < frames.size(); ++centre) {
    const ssrcl::Image own = ssrcl::temporalBlend(window(frames), centre, {});
    EXPECT_EQ(ssrcl::temporalBlend(shared, centre, {}).data, own.data) << "centre " << centre;
    EXPECT_NE(own.data, frames[centre].reflection.data);  // it did blend
  }
  AnalyticFrame half = makeFrame(0, 0.2);
  half.reflection = ssrcl::Image(kW / 2, kH, 4);
  half.depth = ssrcl::Image(kW / 2, kH, 1);
  half.normal = ssrcl::Image(kW / 2, kH, 3);
  half.camera.width = kW / 2;
  shared[1].statistics = ssrcl::temporalFrameStatistics(window({half})[0]);
  EXPECT_THROW(ssrcl::temporalBlend(shared, 0, {}), ssrcl::Error);
  half.camera.width = kW;  // images not of the camera's size
  EXPECT_THROW(ssrcl::temporalFrameStatistics(window({half})[0]), ssrcl::Error);
  // The statistics hold each pixel's world point and normal: a frame without its normals has none.
  std::vector<AnalyticFrame> bare{makeFrame(0, 0.2)};  // outlives the window that points into it
  std::vector<ssrcl::TemporalFrame> noNormals = window(bare);
  noNormals[0].normal = nullptr;
  EXPECT_THROW(ssrcl::temporalFrameStatistics(noNormals[0]), ssrcl::Error);
  bare[0].normal = ssrcl::Image(kW, kH / 2, 3);
  EXPECT_THROW(ssrcl::temporalFrameStatistics(window(bare)[0]), ssrcl::Error);
}

}  // namespace
