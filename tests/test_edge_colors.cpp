// Edge colours (TraceSettings::edgeColors, kernels/setup.cl): a renderer writes each pixel's depth
// from one sample and its colour from all of them, so the wall pixels around a bright lamp hold
// the lamp's light. A mirror ray that reaches the wall beside the lamp sees the wall, as the exact
// reflection says; read from the colour pass as written it takes the lamp's share too.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/vec4.hpp>
#include <iostream>
#include <vector>

#include "device_frame_stages.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/pipeline.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl;
using namespace ssrcl::test;
using glm::dvec3;

constexpr double kWall = 0.5, kLamp = 20.0;

// A mirror floor before an evenly lit wall, a small bright lamp floating in front of it.
Scene lampBeforeWall() {
  auto flat = [](double value, double roughness) {
    Material m;
    m.base = dvec3(value);
    m.roughness = roughness;
    m.textured = false;
    return m;
  };
  Scene s;
  s.name = "lamp_before_wall";
  s.primitives = {rectangle("floor", dvec3(0.0), dvec3(0, 1, 0), 30, 30, flat(0.2, 0.0)),
                  rectangle("wall", dvec3(0, 4, -12), dvec3(0, 0, 1), 30, 4, flat(kWall, 1.0)),
                  sphere("lamp", dvec3(0.3, 2.2, -6), 0.45, flat(kLamp, 1.0))};
  s.view.eye = dvec3(0, 1.2, 6);
  s.view.target = dvec3(0, 1.0, -12);
  return s;
}

// The colour pass as a renderer writes it: the mean of 4x4 samples over each pixel.
Image antialiasedColor(const Scene& scene, const Camera& camera) {
  constexpr int kSide = 4;
  Image color(camera.width, camera.height, 3);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      dvec3 sum(0.0);
      for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i)
          sum += colorAt(scene, intersect(scene, primaryRay(camera, x + (i + 0.5) / kSide, y + (j + 0.5) / kSide)));
      for (int c = 0; c < 3; ++c) color.at(x, y, c) = float(sum[c] / (kSide * kSide));
    }
  return color;
}

// The lamp scene rendered once for every test: its camera, G-buffer, exact reflection and colour.
struct LampFrame {
  Scene scene = lampBeforeWall();
  Camera camera = makeCamera(scene.view, 320, 180);
  AnalyticGBuffer g = renderGBuffer(scene, camera);
  MirrorTruth truth = exactMirrorReflection(scene, camera, g);
  Image color = antialiasedColor(scene, camera);
};
const LampFrame& lampFrame() {
  static const LampFrame frame;
  return frame;
}

struct WallError {
  int pixels = 0, bright = 0;  // floor pixels whose exact reflection is the wall; of them, those read over 2x it
  double sum = 0;              // of |pass - wall|
};

WallError mirrorPassOnWall(bool edgeColors) {
  const LampFrame& f = lampFrame();
  const Camera& camera = f.camera;
  const AnalyticGBuffer& g = f.g;
  Pipeline p(testDevice());
  p.setImage("color", f.color);
  p.setImage("depth", g.depth);
  p.setImage("normal", g.normal);
  p.setImage("roughness", g.roughness);
  p.setCamera(camera);
  p.settings().edgeColors = edgeColors;
  p.commit();
  p.execute();
  const Image pass = p.output("reflection");
  WallError e;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const MirrorSample& s = f.truth.at(x, y);
      const float a = pass.at(x, y, 3);
      if (g.hit(x, y).primitive != 0 || s.cls != ReflectionClass::Visible || s.hit.primitive != 1 || !(a > 0.5f))
        continue;
      const double ours = pass.at(x, y, 0) / a;
      ++e.pixels;
      e.bright += ours > 2 * kWall;
      e.sum += std::abs(ours - kWall);
    }
  return e;
}

TEST(EdgeColors, MirrorRaysBesideALampSeeTheWallBehindIt) {
  const WallError on = mirrorPassOnWall(true), off = mirrorPassOnWall(false);
  std::cout << "floor pixels reflecting the wall: " << on.pixels << "; read over twice the wall: " << on.bright
            << " (colour pass as written: " << off.bright << "); mean |error| " << on.sum / on.pixels << " ("
            << off.sum / off.pixels << ")\n";
  ASSERT_GT(on.pixels, 5000);
  EXPECT_EQ(on.pixels, off.pixels);
  // The scene must put hits on the wall's edge pixels: as written, they read the lamp's light
  // (measured: 33 pixels over twice the wall, mean error 0.027). Held to the wall's light they
  // read it (9 and 0.016: the rest are hits a pixel off, on the lamp's own edge).
  EXPECT_GT(off.bright, 20);
  EXPECT_LE(on.bright, off.bright / 2);
  EXPECT_LT(on.sum, 0.75 * off.sum);
}

// What hits read (the colour pyramid's level 0, setup's output) of `g` with `color`.
std::vector<glm::vec4> hitColors(const AnalyticGBuffer& g, const Image& color, const Camera& camera, bool edgeColors) {
  GBuffer frame = g;
  frame.color = color;
  TraceSettings s = qualityPreset("medium");
  s.edgeColors = edgeColors;
  bench::DeviceFrameStages stages(testDevice(), frame, camera, s);
  stages.run();
  std::vector<glm::vec4> level0 = stages.colorPyramid();
  level0.resize(size_t(camera.width) * camera.height);
  return level0;
}

// Whether pixel (x, y) has a pixel showing primitive `k` (-1: the sky) among its eight neighbours.
bool beside(const AnalyticGBuffer& g, int x, int y, int k) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = x + dx, qy = y + dy;
      if ((dx || dy) && qx >= 0 && qy >= 0 && qx < g.width && qy < g.height && g.hit(qx, qy).primitive == k)
        return true;
    }
  return false;
}

// Which pixels change: the wall's beside the nearer lamp and floor, to the wall's light exactly; not
// the lamp's own edge, whose mix a ray passing just beside it may take.
TEST(EdgeColors, TheSurfaceBehindAnEdgeTakesItsOwnLightAndTheNearerObjectKeepsItsMix) {
  const LampFrame& f = lampFrame();
  const Camera& camera = f.camera;
  const AnalyticGBuffer& g = f.g;
  const std::vector<glm::vec4> on = hitColors(g, f.color, camera, true), off = hitColors(g, f.color, camera, false);
  int wallBesideLamp = 0, mixedWall = 0, lampEdge = 0, mixedLamp = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const size_t i = size_t(y) * camera.width + x;
      const int k = g.hit(x, y).primitive;
      if (k == 1 && (beside(g, x, y, 2) || beside(g, x, y, 0))) {  // the wall beside a nearer surface: its light
        EXPECT_FLOAT_EQ(on[i].x, float(kWall)) << x << "," << y;
        if (beside(g, x, y, 2)) {
          ++wallBesideLamp;
          mixedWall += off[i].x > 2 * kWall;
        }
      } else if (k == 1) {  // elsewhere (beside the sky too) as written
        EXPECT_EQ(on[i], off[i]) << x << "," << y;
      } else if (k == 2 && (beside(g, x, y, 1) || beside(g, x, y, 0))) {  // the lamp's edge: as written
        ++lampEdge;
        EXPECT_EQ(on[i], off[i]) << x << "," << y;
        mixedLamp += off[i].x < 0.9 * kLamp;
      }
    }
  std::cout << wallBesideLamp << " wall pixels beside the lamp (" << mixedWall << " holding its light as written), "
            << lampEdge << " of the lamp's edge (" << mixedLamp << " mixed)\n";
  EXPECT_GT(mixedWall, 20);
  EXPECT_GT(mixedLamp, 20);
}

// A surface's own steep slope is no nearer object: a textured floor's last rows before the sky,
// whose depth grows by several percent a row, keep their colour (mixed with the sky's) as written.
TEST(EdgeColors, AFloorsOutlineAgainstTheSkyKeepsItsColour) {
  Scene scene;
  scene.name = "floor_to_sky";
  scene.primitives = {rectangle("floor", dvec3(0.0), dvec3(0, 1, 0), 12, 12, Material{dvec3(0.7, 0.6, 0.5)})};
  scene.view.eye = dvec3(0, 0.6, 8);
  scene.view.target = dvec3(0, 0.2, -12);
  const Camera camera = makeCamera(scene.view, 240, 135);
  const AnalyticGBuffer g = renderGBuffer(scene, camera);
  const Image color = antialiasedColor(scene, camera);
  const std::vector<glm::vec4> on = hitColors(g, color, camera, true), off = hitColors(g, color, camera, false);
  int outline = 0, steep = 0;
  for (int y = 1; y + 1 < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      if (g.hit(x, y).primitive != 0 || !beside(g, x, y, -1)) continue;
      const size_t i = size_t(y) * camera.width + x;
      ++outline;
      steep += g.hit(x, y + 1).primitive == 0 && g.depth.at(x, y + 1, 0) < 0.98f * g.depth.at(x, y, 0);
      EXPECT_EQ(on[i], off[i]) << x << "," << y;
    }
  std::cout << outline << " floor pixels beside the sky, " << steep << " of them over 2% deeper than the row in\n";
  EXPECT_GT(steep, 100);
}

}  // namespace
