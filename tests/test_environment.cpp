// Environment fill (issue 13 item 4) against independent truth: analytic environments looked up
// along exactly reflected rays in double precision, a double-precision quadrature of the GGX lobe,
// Cycles' own rendering of the world (Blender's mapping), hostile and unusable files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using glm::dvec3;
using Radiance = std::function<dvec3(const dvec3&)>;
constexpr double kPi = 3.14159265358979323846;

// Blender's world mapping (Cycles' direction_to_equirectangular), with v = 0 the top row.
glm::dvec2 blenderUv(const dvec3& d) {
  return {0.5 - std::atan2(d.y, d.x) / (2 * kPi), 0.5 - std::atan2(d.z, std::hypot(d.x, d.y)) / kPi};
}

// An equirect image of `radiance` sampled at texel centres (the inverse of blenderUv).
ssrcl::Image equirect(int width, const Radiance& radiance) {
  ssrcl::Image img(width, width / 2, 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double phi = kPi * (1 - 2 * (x + 0.5) / img.width), elevation = kPi * (0.5 - (y + 0.5) / img.height);
      const dvec3 d(std::cos(elevation) * std::cos(phi), std::cos(elevation) * std::sin(phi), std::sin(elevation));
      const dvec3 L = radiance(d);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(L[c]);
    }
  return img;
}

// A floor z = 0 seen from above (world +Z up, as Blender): every reflected ray climbs away from
// the only surface, so the screen holds none of any lobe (A = 0) and the pass is the environment.
struct FloorView {
  ssrcl::Camera camera;
  ssrcl::GBuffer gbuffer;
  std::vector<dvec3> reflected;  // exact mirror direction of each pixel centre, world space
};

FloorView floorView(float roughness) {
  ssrcl::test::ViewParams params;
  params.eye = {0.3, -3.0, 4.0};
  params.target = {0.0, 2.0, 0.0};
  params.up = {0, 0, 1};
  FloorView v;
  v.camera = ssrcl::test::makeCamera(params, 48, 27);
  const int w = v.camera.width, h = v.camera.height;
  v.gbuffer.color = ssrcl::Image(w, h, 3);
  v.gbuffer.depth = ssrcl::Image(w, h, 1);
  v.gbuffer.normal = ssrcl::Image(w, h, 3);
  v.gbuffer.roughness = ssrcl::Image(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const ssrcl::test::Ray ray = ssrcl::test::primaryRay(v.camera, x + 0.5, y + 0.5);
      const dvec3 p = ray.origin + ray.direction * (-ray.origin.z / ray.direction.z);
      v.gbuffer.depth.at(x, y, 0) = float(ssrcl::test::planarDepth(v.camera, p));
      v.gbuffer.normal.at(x, y, 2) = 1.0f;
      v.gbuffer.roughness.at(x, y, 0) = roughness;
      for (int c = 0; c < 3; ++c) v.gbuffer.color.at(x, y, c) = 0.5f;
      v.reflected.push_back(glm::normalize(ray.direction * dvec3(1, 1, -1)));
    }
  return v;
}

ssrcl::Image trace(const FloorView& view, const ssrcl::EnvironmentMap& env, float rotation = 0.0f,
                   float intensity = 1.0f) {
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline pipeline(device);
  pipeline.setGBuffer(view.gbuffer);
  pipeline.setCamera(view.camera);
  pipeline.setEnvironment(env);
  pipeline.settings().environmentRotation = rotation;
  pipeline.settings().environmentIntensity = intensity;
  pipeline.commit();
  pipeline.execute();
  return pipeline.output("reflection");
}

// A smooth analytic sky: linear in the direction, so its GGX-lobe mean has a closed form in the
// lobe's mean direction (see lobeMeanCosine).
dvec3 linearSky(const dvec3& d) { return dvec3(1.0) + 0.5 * d; }

dvec3 rotateZ(const dvec3& d, double degrees) {
  const double a = degrees * kPi / 180, c = std::cos(a), s = std::sin(a);
  return {c * d.x - s * d.y, s * d.x + c * d.y, d.z};
}

// Mean of l.n over the prefiltered lobe (normal = view = n): the weight of direction l is the
// GGX pdf of l, D(h) / 4, times n.l, as environment.hpp defines the levels. Midpoint quadrature
// over the hemisphere in double precision.
double lobeMeanCosine(double alpha) {
  const double a2 = alpha * alpha;
  double weighted = 0, total = 0;
  constexpr int kSteps = 20000;
  for (int i = 0; i < kSteps; ++i) {
    const double theta = (i + 0.5) / kSteps * kPi / 2, cosL = std::cos(theta);
    const double cosH = std::cos(theta / 2);  // h halfway between n and l
    const double denom = cosH * cosH * (a2 - 1) + 1;
    const double w = a2 / (kPi * denom * denom) / 4 * cosL * std::sin(theta);
    weighted += w * cosL;
    total += w;
  }
  return weighted / total;
}

TEST(Environment, ConstantEnvironmentFillsWholeMissesExactly) {
  const ssrcl::EnvironmentMap env =
      ssrcl::prefilterEnvironment(equirect(64, [](const dvec3&) { return dvec3(0.3, 0.6, 0.9); }));
  for (float roughness : {0.0f, 0.3f, 0.55f, 1.0f}) {
    const FloorView view = floorView(roughness);
    const ssrcl::Image out = trace(view, env, 0.0f, 2.0f);
    for (int i = 0; i < view.camera.width * view.camera.height; ++i) {
      ASSERT_EQ(out.data[4 * i + 3], 0.0f) << "the floor's lobe leaves the screen: A = 0";
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(out.data[4 * i + c], 2.0 * (0.3 + 0.3 * c), 1e-5) << "roughness " << roughness;
    }
  }
}

TEST(Environment, MirrorReadsBlenderMappingAlongTheReflectedRay) {
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(equirect(512, linearSky));
  const FloorView view = floorView(0.0f);
  // Rotation turns the environment about +Z: the lookup reads the direction rotated by the angle.
  for (float rotation : {0.0f, 90.0f, -37.5f}) {
    const ssrcl::Image out = trace(view, env, rotation);
    double worst = 0;
    for (size_t i = 0; i < view.reflected.size(); ++i) {
      const dvec3 expected = linearSky(rotateZ(view.reflected[i], rotation));
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(out.data[4 * i + c] - expected[c]));
    }
    EXPECT_LT(worst, 2e-3) << "rotation " << rotation;
  }
}

// An edge pixel holding two surfaces: Cycles averages their normals over the pixel's samples
// but writes the depth of its first sample alone, so the pixel's point lies on one surface while
// its normal (here 0.6 floor + 0.4 a wall's, length 0.72) faces neither. On the floor's plane its
// fill reads along the floor's mirror direction (its full-length neighbours' surface); off every
// neighbour's plane nothing says which surface it is on, and it reads along the mean's.
TEST(Environment, MixedEdgePixelFillsAlongTheSurfaceItsDepthIsOn) {
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(equirect(512, linearSky));
  FloorView view = floorView(0.0f);
  const dvec3 mixed = 0.6 * dvec3(0, 0, 1) + 0.4 * dvec3(1, 0, 0);
  const int onFloor = 20, offPlane = 32;
  for (int y = 0; y < view.camera.height; ++y)
    for (int x : {onFloor, offPlane}) {
      for (int c = 0; c < 3; ++c) view.gbuffer.normal.at(x, y, c) = float(mixed[c]);
      // In front of the floor: a point behind it would send its rays into the floor's underside
      // (the trace stops them there, black), which is the trace's question, not the fill's.
      if (x == offPlane) view.gbuffer.depth.at(x, y, 0) *= 0.9f;
    }
  const ssrcl::Image out = trace(view, env);
  const dvec3 n = glm::normalize(mixed);
  double worstFloor = 0, worstOff = 0, averagedFloor = 0;
  for (int y = 0; y < view.camera.height; ++y) {
    const int floorPixel = y * view.camera.width + onFloor, offPixel = y * view.camera.width + offPlane;
    const dvec3 d = ssrcl::test::primaryRay(view.camera, offPlane + 0.5, y + 0.5).direction;
    const dvec3 averaged = linearSky(d - 2 * glm::dot(d, n) * n);
    const dvec3 dFloor = ssrcl::test::primaryRay(view.camera, onFloor + 0.5, y + 0.5).direction;
    const dvec3 floorAveraged = linearSky(dFloor - 2 * glm::dot(dFloor, n) * n);
    for (int c = 0; c < 3; ++c) {
      worstFloor =
          std::max(worstFloor, std::abs(out.data[4 * floorPixel + c] - linearSky(view.reflected[floorPixel])[c]));
      worstOff = std::max(worstOff, std::abs(out.data[4 * offPixel + c] - averaged[c]));
      averagedFloor = std::max(averagedFloor, std::abs(floorAveraged[c] - linearSky(view.reflected[floorPixel])[c]));
    }
  }
  EXPECT_GT(averagedFloor, 0.1) << "the averaged normal's reflection must be told apart from the floor's";
  EXPECT_LT(worstFloor, 2e-3) << "on the floor's plane: the floor's mirror direction";
  EXPECT_LT(worstOff, 2e-3) << "off every neighbour's plane: the averaged normal's";
}

// A mirror floor whose normal alternates from column to column (ripples a pixel wide): the fill is
// the mean of the environment along four normals of the pixel's footprint, at (+-0.21, +-0.21) px,
// each bilinear between the pixel centres around it (Blender's pixel filter's spread, as Cycles'
// pixel averages its footprint), not the point sample along the pixel's own normal. The truth is
// that rule in double precision on the analytic environment; the point sample is far off it.
TEST(Environment, RippledFloorFillsWithItsFootprintsMean) {
  const Radiance sky = [](const dvec3& d) { return dvec3(std::exp(3.0 * d.x), std::exp(2.0 * d.y), 1.0 + d.z); };
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(equirect(2048, sky));
  FloorView view = floorView(0.0f);
  const int w = view.camera.width, h = view.camera.height;
  const auto normalAt = [](int x) { return glm::normalize(dvec3(x % 2 ? 0.1 : -0.1, 0.0, 1.0)); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) view.gbuffer.normal.at(x, y, c) = float(normalAt(x)[c]);
  const ssrcl::Image out = trace(view, env);
  const double spread = 0.21;
  double worst = 0, pointSample = 0;
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      const dvec3 d = ssrcl::test::primaryRay(view.camera, x + 0.5, y + 0.5).direction;
      dvec3 mean(0.0);
      for (int k = 0; k < 4; ++k) {
        // Bilinear between the centres around (x + ox, y +- spread): the normal depends on x alone.
        const double ox = (k & 1) ? spread : -spread, fx = ox > 0 ? ox : 1 + ox;
        const int x0 = ox > 0 ? x : x - 1;
        const dvec3 n = glm::normalize((1 - fx) * normalAt(x0) + fx * normalAt(x0 + 1));
        mean += 0.25 * sky(d - 2 * glm::dot(d, n) * n);
      }
      const dvec3 own = sky(d - 2 * glm::dot(d, normalAt(x)) * normalAt(x));
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(out.data[4 * (y * w + x) + c] - mean[c]) / mean[c]);
        pointSample = std::max(pointSample, std::abs(own[c] - mean[c]) / mean[c]);
      }
    }
  EXPECT_GT(pointSample, 0.05) << "the point sample must be told apart from the footprint's mean";
  EXPECT_LT(worst, 0.01) << "relative to the footprint's mean";
}

TEST(Environment, RoughLobesAverageTheEnvironmentOverTheGgxLobe) {
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(equirect(512, linearSky));
  // Roughness 0.5 and 1.0 fall on prefiltered levels; 0.3 between two.
  for (float roughness : {0.3f, 0.5f, 1.0f}) {
    const FloorView view = floorView(roughness);
    const ssrcl::Image out = trace(view, env);
    const double k = lobeMeanCosine(double(roughness) * roughness);
    double worst = 0, unfiltered = 0;
    for (size_t i = 0; i < view.reflected.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double truth = 1.0 + 0.5 * k * view.reflected[i][c];
        worst = std::max(worst, std::abs(out.data[4 * i + c] - truth));
        unfiltered = std::max(unfiltered, std::abs(linearSky(view.reflected[i])[c] - truth));
      }
    // The point sample along the reflection is off by `unfiltered`; the prefiltered lookup at
    // least three times less (between two levels, their mixture is not quite the lobe between).
    EXPECT_LT(worst, 0.01) << "roughness " << roughness << ", lobe mean cosine " << k;
    EXPECT_LT(worst, unfiltered / 3) << "roughness " << roughness;
  }
}

TEST(Environment, FillAddsTheEnvironmentForTheMissedShareOnly) {
  const ssrcl::test::Scene scene = ssrcl::test::makeScene("spheres_on_mirror");
  const ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, 96, 54);
  const ssrcl::test::AnalyticGBuffer gbuffer = ssrcl::test::renderGBuffer(scene, camera);
  const ssrcl::EnvironmentMap env =
      ssrcl::prefilterEnvironment(equirect(64, [](const dvec3&) { return dvec3(0.25, 0.5, 1.0); }));
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline pipeline(device);
  pipeline.setGBuffer(gbuffer);
  pipeline.setCamera(camera);
  pipeline.settings().constantRoughness = 0.2f;
  pipeline.commit();
  pipeline.execute();
  const ssrcl::Image premultiplied = pipeline.output("reflection");
  pipeline.setEnvironment(env);
  pipeline.commit();
  pipeline.execute();
  const ssrcl::Image filled = pipeline.output("reflection");
  int partial = 0;
  for (int i = 0; i < camera.width * camera.height; ++i) {
    const float a = premultiplied.data[4 * i + 3];
    ASSERT_EQ(filled.data[4 * i + 3], a) << "A stays the screen-space fraction";
    const bool surface = gbuffer.depth.data[i] < ssrcl::test::kSkyDepth;
    partial += a > 0.05f && a < 0.95f;
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(filled.data[4 * i + c], premultiplied.data[4 * i + c] + (surface ? (1 - a) * 0.25 * (1 << c) : 0.0),
                  1e-4)
          << "pixel " << i;
  }
  EXPECT_GT(partial, 20) << "the scene should have pixels whose lobe is partly on screen";
}

TEST(Environment, HostileValuesGiveFiniteOutput) {
  ssrcl::Image img = equirect(64, linearSky);
  const float hostile[] = {NAN, INFINITY, -INFINITY, -5.0f, 3e38f, 1e-45f};
  for (size_t i = 0; i < img.data.size(); i += 7) img.data[i] = hostile[(i / 7) % 6];
  const ssrcl::EnvironmentMap env = ssrcl::prefilterEnvironment(img);
  for (float roughness : {0.0f, 0.4f, 1.0f}) {
    const ssrcl::Image out = trace(floorView(roughness), env, 0.0f, 1e6f);
    for (float v : out.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << "roughness " << roughness;
  }
}

TEST(Environment, UnusableFilesAreRefusedNamingTheFile) {
  ssrcl::test::TempDir dir("env");
  auto expectError = [](const std::string& path, ssrcl::ErrorCode code, const std::string& says) {
    try {
      ssrcl::loadEnvironmentMap(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const ssrcl::Error& e) {
      EXPECT_EQ(e.code(), code) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  expectError(dir.file("missing.exr"), ssrcl::ErrorCode::IoError, "cannot read");
  const std::string wide = dir.file("wide.exr");
  ssrcl::test::writeExr(wide, 12, 4, {{"R", std::vector<float>(48, 1.0f)}, {"G", std::vector<float>(48, 1.0f)},
                                     {"B", std::vector<float>(48, 1.0f)}});
  expectError(wide, ssrcl::ErrorCode::InvalidInput, "2:1");
  const std::string grey = dir.file("grey.exr");
  ssrcl::test::writeExr(grey, 8, 4, {{"Y", std::vector<float>(32, 1.0f)}});
  expectError(grey, ssrcl::ErrorCode::InvalidInput, "R, G, B");
  const std::string text = dir.file("text.exr");
  std::ofstream(text) << "not an image";
  expectError(text, ssrcl::ErrorCode::IoError, "cannot read");
}

TEST(Environment, LoadedFileMatchesTheImageItHolds) {
  ssrcl::test::TempDir dir("env");
  const std::string path = dir.file("sky.exr");
  const ssrcl::Image img = equirect(32, linearSky);
  std::vector<ssrcl::test::ExrChannel> channels(3);
  for (int c = 0; c < 3; ++c) {
    channels[c].name = std::string(1, "RGB"[c]);
    for (size_t i = 0; i < img.data.size() / 3; ++i) channels[c].values.push_back(img.data[3 * i + c]);
  }
  ssrcl::test::writeExr(path, 32, 16, channels);
  const ssrcl::EnvironmentMap env = ssrcl::loadEnvironmentMap(path);
  EXPECT_EQ(env.source, path);
  ASSERT_GE(env.levels.size(), 2u);
  EXPECT_EQ(env.levels[0].data, img.data) << "level 0 is the map itself";
}

// Blender's mapping, checked against Blender: make_env_corpus.py renders the world alone
// (env_mapping: horizon blocks and the sun in view; env_mapping_rot30: the same through a Mapping
// node turned 30 degrees about Z), so Cycles' Combined is the environment along each pixel's view
// ray, blurred only by the pixel filter. Mean relative error of a lookup rule over the frame:
double mappingError(const std::string& stem, const std::function<glm::dvec2(const dvec3&)>& uvOf) {
  const std::string dir = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/environment/";
  static const ssrcl::EnvironmentMap env = ssrcl::loadEnvironmentMap(dir + "sky.exr");  // prefiltered once
  ssrcl::GBufferSource source;
  source.file = dir + stem + ".exr";
  source.glossyPasses = false;
  const ssrcl::GBuffer render = ssrcl::loadGBuffer(source);
  const ssrcl::Camera camera = ssrcl::loadCameraJson(dir + stem + ".camera.json");
  const ssrcl::Image& sky = env.levels[0];
  double error = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::dvec2 uv = uvOf(ssrcl::test::primaryRay(camera, x + 0.5, y + 0.5).direction);
      const int sx = std::clamp(int(uv.x * sky.width), 0, sky.width - 1);
      const int sy = std::clamp(int(uv.y * sky.height), 0, sky.height - 1);
      const dvec3 ours(sky.at(sx, sy, 0), sky.at(sx, sy, 1), sky.at(sx, sy, 2));
      const dvec3 cycles(render.color.at(x, y, 0), render.color.at(x, y, 1), render.color.at(x, y, 2));
      error += glm::length(ours - cycles) / glm::length(cycles);
    }
  return error / (camera.width * camera.height);
}

TEST(Environment, BlenderMappingMatchesCycles) {
  const double documented = mappingError("env_mapping", blenderUv);
  EXPECT_LT(documented, 0.03);
  // The likely mistakes fit clearly worse: azimuth mirrored, a quarter turn off, upside down.
  const double mirrored = mappingError("env_mapping", [](const dvec3& d) {
    const glm::dvec2 uv = blenderUv(d);
    return glm::dvec2(1 - uv.x, uv.y);
  });
  const double turned = mappingError("env_mapping", [](const dvec3& d) { return blenderUv(rotateZ(d, 90)); });
  const double flipped = mappingError("env_mapping", [](const dvec3& d) {
    const glm::dvec2 uv = blenderUv(d);
    return glm::dvec2(uv.x, 1 - uv.y);
  });
  for (double wrong : {mirrored, turned, flipped}) EXPECT_GT(wrong, 3 * documented);
}

TEST(Environment, RotationMatchesBlenderMappingNode) {
  // environmentRotation = 30 reads the direction turned +30 degrees about +Z, as Blender's
  // Mapping node with Rotation Z = 30 does; the opposite sense fits clearly worse.
  const double documented = mappingError("env_mapping_rot30", [](const dvec3& d) { return blenderUv(rotateZ(d, 30)); });
  const double opposite = mappingError("env_mapping_rot30", [](const dvec3& d) { return blenderUv(rotateZ(d, -30)); });
  EXPECT_LT(documented, 0.03);
  EXPECT_GT(opposite, 3 * documented);
}

const std::string kCorpus = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/environment/";

// The validation on Cycles (docs/BENCHMARKS.md has the table): on a scene lit by the HDRI, the
// filled pass is closer to Cycles' glossy passes than the premultiplied one and than EEVEE's
// Specular Light with its world probe.
TEST(Environment, FilledPassBeatsEeveeAgainstCycles) {
  const ssrcl::test::CyclesReference ref = ssrcl::test::loadCyclesReference(kCorpus + "env_plaza.exr");
  const auto& all = ref.groups.front().second;
  const ssrcl::EnvironmentMap env = ssrcl::loadEnvironmentMap(kCorpus + "sky.exr");
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline pipeline(device);
  pipeline.setGBuffer(ref.gbuffer);
  pipeline.setCamera(ref.camera);
  pipeline.commit();
  pipeline.execute();
  const double premultiplied = ssrcl::test::referenceError(ref, pipeline.output("reflection"), all).psnr;
  pipeline.setEnvironment(env);
  pipeline.commit();
  pipeline.execute();
  const double filled = ssrcl::test::referenceError(ref, pipeline.output("reflection"), all).psnr;

  const double peer =
      ssrcl::test::referenceError(ref, ssrcl::test::eeveeSpecular(kCorpus + "env_plaza.eevee.exr", false), all).psnr;
  EXPECT_GT(filled, peer + 1.0) << "premultiplied " << premultiplied << " dB";
  EXPECT_GT(filled, premultiplied + 5.0);
}

TEST(Environment, CliFillsAndRecordsTheEnvironment) {
  ssrcl::test::TempDir dir("env_cli");
  const std::string out = dir.file("out.exr"), sky = kCorpus + "sky.exr";
  const std::string trace = std::string(SSRCL_CLI) + " trace " + ssrcl::test::shellQuote(kCorpus + "env_tiles.exr");
  const ssrcl::test::CommandResult ok =
      ssrcl::test::runCommand(trace + " -o " + ssrcl::test::shellQuote(out) + " --environment " +
                              ssrcl::test::shellQuote(sky) + " --environment-rotation 30 --environment-intensity 1.5");
  ASSERT_EQ(ok.exitCode, 0) << ok.output;
  const auto inputs = nlohmann::json::parse(ssrcl::test::stringAttribute(out, "ssrcl/inputs"));
  EXPECT_EQ(inputs.at("environment"), sky);
  const auto settings = nlohmann::json::parse(ssrcl::test::stringAttribute(out, "ssrcl/settings"));
  EXPECT_EQ(settings.at("environmentRotation"), 30.0);
  EXPECT_EQ(settings.at("environmentIntensity"), 1.5);

  // A missing file is named, with the usage exit code, before any tracing and with nothing written.
  const std::string missing = dir.file("no_such_sky.exr"), out2 = dir.file("out2.exr");
  const ssrcl::test::CommandResult bad = ssrcl::test::runCommand(
      trace + " -o " + ssrcl::test::shellQuote(out2) + " --environment " + ssrcl::test::shellQuote(missing));
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find(missing), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(out2));
}

}  // namespace
