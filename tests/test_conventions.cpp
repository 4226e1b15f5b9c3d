// Passes in other renderers' conventions (issue 12), made from the bundled Blender samples: each
// variant traces, through `ssrcl trace` as a user runs it, to the original's reflection pass; each
// wrong declaration is refused before tracing with exit 2, naming the pass and the fixing option.
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "io/exr_header_camera.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace {

using ssrcl::test::ExrChannel;
using ssrcl::test::ExrOptions;
using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

std::string samplePath(const std::string& name, const char* ext) {
  return std::string(SSRCL_SOURCE_DIR) + "/samples/blender/" + name + "/" + name + ext;
}

// A sample's passes as Blender wrote them, in world space and planar depth, row by row.
struct Sample {
  std::string name;
  ssrcl::GBuffer g;
  ssrcl::Camera camera;
  int w = 0, h = 0;
  std::string original;  // its reflection pass, traced once from the untouched file (originalPass)

  bool sky(int i) const { return !(g.depth.data[i] < 1e9f); }
  // The camera-space point of pixel i, unprojected through the projection's own depth mapping.
  glm::dvec3 eyePoint(int i) const {
    const int x = i % w, y = i / w;
    const double d = g.depth.data[i];
    const glm::dvec4 clip = camera.projection * glm::dvec4(0.0, 0.0, -d, 1.0);
    const glm::dvec4 ndc(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, clip.z / clip.w, 1.0);
    const glm::dvec4 p = glm::inverse(camera.projection) * ndc;
    return glm::dvec3(p) / p.w;
  }
  std::vector<float> channel(const ssrcl::Image& image, int c) const {
    std::vector<float> v(size_t(w) * h);
    for (size_t i = 0; i < v.size(); ++i) v[i] = image.data[i * image.channels + c];
    return v;
  }
};

// Channel sets of a variant. Color and roughness are the original's, under the given names.
std::vector<ExrChannel> baseChannels(const Sample& s, const std::string& color, const std::string& roughness,
                                     const char* components = "RGB") {
  return {{color + components[0], s.channel(s.g.color, 0)},
          {color + components[1], s.channel(s.g.color, 1)},
          {color + components[2], s.channel(s.g.color, 2)},
          {roughness, s.channel(s.g.roughness, 0)}};
}

std::vector<float> radialDepth(const Sample& s) {
  std::vector<float> r(size_t(s.w) * s.h);
  for (size_t i = 0; i < r.size(); ++i) r[i] = s.sky(int(i)) ? 1e10f : float(glm::length(s.eyePoint(int(i))));
  return r;
}

// World-space positions; with `eye`, camera (OpenGL eye) space instead: a wrongly written P pass.
std::vector<ExrChannel> positions(const Sample& s, const std::string& prefix, bool eye = false) {
  std::vector<float> p[3];
  const glm::dmat4 eyeToWorld = eye ? glm::dmat4(1.0) : glm::inverse(s.camera.view);
  for (int i = 0; i < s.w * s.h; ++i) {
    const glm::dvec3 world = s.sky(i) ? glm::dvec3(0.0) : glm::dvec3(eyeToWorld * glm::dvec4(s.eyePoint(i), 1.0));
    for (int c = 0; c < 3; ++c) p[c].push_back(float(world[c]));
  }
  return {{prefix + "X", p[0]}, {prefix + "Y", p[1]}, {prefix + "Z", p[2]}};
}

// Camera spaces by the signs that take OpenGL eye space (x right, y up, -z forward) to them:
// OpenEXR/RenderMan's (+z forward) and OpenCV's (y down, +z forward: V-Ray for Maya's normals).
const glm::dvec3 kGlCamera(1, 1, 1), kExrCamera(1, 1, -1), kCvCamera(1, -1, -1);

std::vector<ExrChannel> cameraNormals(const Sample& s, const std::string& prefix, const char* axes,
                                      const glm::dvec3& signs) {
  std::vector<float> n[3];
  const glm::dmat3 toEye(s.camera.view);
  for (int i = 0; i < s.w * s.h; ++i) {
    const glm::dvec3 e =
        signs * (toEye * glm::dvec3(s.g.normal.data[3 * i], s.g.normal.data[3 * i + 1], s.g.normal.data[3 * i + 2]));
    for (int c = 0; c < 3; ++c) n[c].push_back(float(e[c]));
  }
  return {{prefix + axes[0], n[0]}, {prefix + axes[1], n[1]}, {prefix + axes[2], n[2]}};
}

std::vector<ExrChannel> worldNormals(const Sample& s, const std::string& prefix, int negatedAxis = -1,
                                     const char* axes = "XYZ") {
  std::vector<ExrChannel> n = {{prefix + axes[0], s.channel(s.g.normal, 0)},
                               {prefix + axes[1], s.channel(s.g.normal, 1)},
                               {prefix + axes[2], s.channel(s.g.normal, 2)}};
  if (negatedAxis >= 0)
    for (float& v : n[negatedAxis].values) v = -v;
  return n;
}

std::vector<ExrChannel> operator+(std::vector<ExrChannel> a, const std::vector<ExrChannel>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The Imath matrix (row vectors: p'_j = sum_i p_i M[i][j]) of a GLM column-vector map
// (p'_j = sum_i A[i][j] p_i, GLM indexing [column][row]): the same numbers at the same indices.
// addStandardCamera checks the result with Imath's own arithmetic.
Imath::M44f imath(const glm::dmat4& columnVectorMatrix) {
  Imath::M44f m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m[i][j] = float(columnVectorMatrix[i][j]);
  return m;
}

// How a renderer lays out its header camera: OpenEXR's worldToNDC, (0,0) top-left to (1,1)
// bottom-right; worldToScreen in OpenImageIO's screen space, [-1, 1] y up; that screen space under
// the name worldToNDC with arnold/* attributes beside it (as Arnold 4.2 writes it through
// OpenImageIO before 2.2: see ArnoldFileHeaderCamera); and Houdini's, screen space as worldToNDC
// with a worldToCamera looking down -z (see HoudiniHeaderCamera). All but Houdini's worldToCamera
// look down +z.
enum class Projected { StandardNdc, Screen, ArnoldNdc, Houdini };

// The layouts' definitions, checked with Imath's own arithmetic on the sample's surface points.
// `display` is the display window in the sample's pixel coordinates, `c` its camera.
void addStandardCamera(Imf::Header& header, const Sample& s, Projected layout, const ssrcl::Camera& c,
                       const Imath::Box2i& display) {
  const bool houdini = layout == Projected::Houdini;
  const glm::dmat4 flipZ = glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, houdini ? 1 : -1));
  const glm::dmat4 toCamera = flipZ * c.view;
  glm::dmat4 toUnit(1.0);  // clip to homogeneous NDC [0,1], y down; screen space is clip x, y
  if (layout == Projected::StandardNdc) toUnit = glm::dmat4(0.5, 0, 0, 0, 0, -0.5, 0, 0, 0, 0, 1, 0, 0.5, 0.5, 0, 1);
  if (layout == Projected::ArnoldNdc) header.insert("arnold/version", Imf::StringAttribute("Arnold 4.2.16.2"));
  const Imath::M44f camera = imath(toCamera), projected = imath(toUnit * c.projection * c.view);
  for (int i = 0; i < s.w * s.h; i += 997) {
    if (s.sky(i)) continue;
    const glm::dvec3 eye = s.eyePoint(i);
    const glm::dvec3 world = glm::dvec3(glm::inverse(s.camera.view) * glm::dvec4(eye, 1.0));
    Imath::V3f inCamera, n;
    camera.multVecMatrix(Imath::V3f(float(world.x), float(world.y), float(world.z)), inCamera);
    projected.multVecMatrix(Imath::V3f(float(world.x), float(world.y), float(world.z)), n);
    EXPECT_NEAR(inCamera.z, houdini ? eye.z : -eye.z, 1e-3 * std::abs(eye.z));
    if (layout == Projected::StandardNdc) {
      EXPECT_NEAR(n.x * c.width + display.min.x, i % s.w + 0.5, 1e-2);
      EXPECT_NEAR(n.y * c.height + display.min.y, i / s.w + 0.5, 1e-2);
    } else {
      EXPECT_NEAR((n.x + 1) / 2 * c.width + display.min.x, i % s.w + 0.5, 1e-2);
      EXPECT_NEAR((1 - n.y) / 2 * c.height + display.min.y, i / s.w + 0.5, 1e-2);
    }
  }
  header.insert("worldToCamera", Imf::M44fAttribute(camera));
  header.insert(layout == Projected::Screen ? "worldToScreen" : "worldToNDC", Imf::M44fAttribute(projected));
}

// Clip-plane attributes under a renderer's names, here the sample's own planes.
void addClipPlanes(Imf::Header& header, const char* nearName, const char* farName, double n, double f) {
  header.insert(nearName, Imf::FloatAttribute(float(n)));
  header.insert(farName, Imf::FloatAttribute(float(f)));
}

// V-Ray: camera-to-world in V-Ray's camera frame (x right, looking down -y, -z up: see
// VrayFileHeaderCamera) and the horizontal field of view in degrees; the samples' frusta are
// centred (no lens shift), which is all a field of view can describe.
void addVrayCamera(Imf::Header& header, const Sample& s) {
  ASSERT_EQ(s.camera.projection[2][0], 0.0);
  // Columns: V-Ray's x, y, z in eye space (x, -z, -y).
  const glm::dmat4 vrayToEye(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1);
  header.insert("cameraTransform", Imf::M44fAttribute(imath(glm::inverse(s.camera.view) * vrayToEye)));
  header.insert("cameraFov", Imf::FloatAttribute(float(2.0 * std::atan(1.0 / s.camera.projection[0][0]) * 180.0 / M_PI)));
  header.insert("cameraProjection", Imf::IntAttribute(0));
  header.insert("cameraNearClip", Imf::FloatAttribute(float(s.camera.nearPlane)));
  header.insert("cameraFarClip", Imf::FloatAttribute(float(s.camera.farPlane)));
}

// The sample's camera for another display window (pixel coordinates of the original frame):
// each NDC axis re-centred and re-scaled on the window's span, row by row of the clip matrix.
ssrcl::Camera cameraForWindow(const Sample& s, int x0, int y0, int x1, int y1) {
  ssrcl::Camera c = s.camera;
  const double left = 2.0 * x0 / s.w - 1.0, right = 2.0 * (x1 + 1) / s.w - 1.0;
  const double top = 1.0 - 2.0 * y0 / s.h, bottom = 1.0 - 2.0 * (y1 + 1) / s.h;
  const double cx = 0.5 * (left + right), hx = 0.5 * (right - left), cy = 0.5 * (top + bottom),
               hy = 0.5 * (top - bottom);
  for (int col = 0; col < 4; ++col) {
    c.projection[col][0] = (s.camera.projection[col][0] - cx * s.camera.projection[col][3]) / hx;
    c.projection[col][1] = (s.camera.projection[col][1] - cy * s.camera.projection[col][3]) / hy;
  }
  c.width = x1 - x0 + 1;
  c.height = y1 - y0 + 1;
  return c;
}

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

// Two reflection passes agree on every pixel of `reference`'s. Conversions round in float: a ray
// may land a pixel away here and there, and with prefiltered hits (kernels/hit_prefilter.cl) that
// also moves its footprint's weights: measured up to 0.16% of values off (the glossy sample's
// overscan variant), so the bound is 0.2%.
void expectSamePass(const std::string& reference, const std::string& out) {
  const auto a = ssrcl::test::readExr(reference), b = ssrcl::test::readExr(out);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  long long off = 0, pixels = 0;
  double sum = 0.0;
  for (const char* c : {"R", "G", "B", "A", "distance"}) {
    for (size_t i = 0; i < a.channels.at(c).values.size(); ++i) {
      const double d = std::abs(double(a.channels.at(c).values[i]) - b.channels.at(c).values[i]);
      off += d > 1e-3;
      sum += d;
      ++pixels;
    }
  }
  EXPECT_LE(off, pixels / 500) << out;
  EXPECT_LT(sum / pixels, 2e-5) << out;
}

// Refused before tracing, with a message naming `pass` and `fix`.
void expectRefused(const std::string& input, const std::string& options, const std::string& pass,
                   const std::string& fix) {
  const std::string out = input + ".refused.exr";
  const auto r = runCommand(cli("trace " + shellQuote(input) + " " + options + " -o " + shellQuote(out)));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(pass), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(fix), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

class Conventions : public testing::TestWithParam<const char*> {
 protected:
  static inline ssrcl::test::TempDir* dir = nullptr;
  static inline std::map<std::string, Sample> samples;

  static void SetUpTestSuite() { dir = new ssrcl::test::TempDir("ssrcl-conventions"); }
  static void TearDownTestSuite() {
    delete dir;
    dir = nullptr;
    samples.clear();
  }

  // Loaded and traced once per sample, shared by every case.
  const Sample& sample() {
    const std::string name = GetParam();
    auto it = samples.find(name);
    if (it != samples.end()) return it->second;
    Sample s;
    s.name = name;
    ssrcl::GBufferSource source;
    source.file = samplePath(name, ".exr");
    s.g = ssrcl::loadGBuffer(source);
    s.camera = ssrcl::loadCameraJson(samplePath(name, ".camera.json"));
    s.w = s.g.depth.width;
    s.h = s.g.depth.height;
    return samples.emplace(name, std::move(s)).first->second;
  }

  // The untouched sample's reflection pass, traced on first use (ctest runs each case alone).
  const std::string& originalPass() {
    Sample& s = samples.at(GetParam());
    if (s.original.empty()) {
      const std::string out = dir->file(s.name + ".original.exr");
      // Without the glossy passes, which the variants do not carry (they change hits on glossy surfaces).
      const auto r = runCommand(
          cli("trace " + shellQuote(samplePath(s.name, ".exr")) + " --no-glossy-passes -o " + shellQuote(out)));
      EXPECT_EQ(r.exitCode, 0) << r.output;
      s.original = out;
    }
    return s.original;
  }

  std::string variant(const std::string& tag, const std::vector<ExrChannel>& channels, const ExrOptions& options = {},
                      const ssrcl::Camera* sidecar = nullptr) {
    const Sample& s = sample();
    const std::string path = dir->file(s.name + "." + tag + ".exr");
    ssrcl::test::writeExr(path, s.w, s.h, channels, options);
    if (sidecar) ssrcl::saveCameraJson(dir->file(s.name + "." + tag + ".camera.json"), *sidecar);
    return path;
  }

  // Arnold's channel names (R,G,B, Z, N.X,N.Y,N.Z) with `depth` as Z, world normals, and the
  // sample's camera in the header in `layout`, with Arnold's clip-plane attributes if `clip`.
  std::string arnoldNamedVariant(const std::string& tag, Projected layout, const std::vector<float>& depth,
                                 bool clip = false) {
    const Sample& s = sample();
    ExrOptions options;
    options.editHeader = [&](Imf::Header& h) {
      addStandardCamera(h, s, layout, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
      if (clip)
        addClipPlanes(h, "arnold/camera/near_clip", "arnold/camera/far_clip", s.camera.nearPlane, s.camera.farPlane);
    };
    return variant(tag,
                   baseChannels(s, "", "roughness") + std::vector<ExrChannel>{{"Z", depth}} + worldNormals(s, "N."),
                   options);
  }

  // Traces `input` with `options` and compares with the original's pass on its pixels.
  void expectSameAsOriginal(const std::string& input, const std::string& options,
                            const Imath::Box2i* display = nullptr) {
    const Sample& s = sample();
    const std::string out = input + ".refl.exr";
    const auto r = runCommand(cli("trace " + shellQuote(input) + " " + options + " -o " + shellQuote(out)));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectSameAs(out, display);
  }

  void expectSameAs(const std::string& out, const Imath::Box2i* display) {
    const Sample& s = sample();
    if (display) {
      const auto b = ssrcl::test::readExr(out);
      EXPECT_EQ(b.displayWindow, *display);
      EXPECT_EQ(b.dataWindow, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
    }
    expectSamePass(originalPass(), out);
  }
};

const std::string kBlender = "ViewLayer.";

TEST_P(Conventions, RadialDepthAndCameraNormalsByOption) {
  const Sample& s = sample();
  const std::string in = variant(
      "radial", baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                    std::vector<ExrChannel>{{kBlender + "Depth.Z", radialDepth(s)}} +
                    cameraNormals(s, kBlender + "Normal.", "XYZ", kExrCamera),
      {}, &s.camera);
  expectSameAsOriginal(in, "--depth-kind radial --normal-space camera");
  expectRefused(in, "--normal-space camera", "depth pass", "--depth-kind radial");
  expectRefused(in, "--depth-kind radial", "normal pass", "--normal-space camera");
  expectRefused(in, "--depth-kind radial --normal-space camera-gl", "normal pass", "--normal-space camera");
}

TEST_P(Conventions, PositionsInsteadOfDepth) {
  const Sample& s = sample();
  const std::string in = variant("position",
                                 baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                                     positions(s, "P.") + cameraNormals(s, kBlender + "Normal.", "XYZ", kGlCamera),
                                 {}, &s.camera);
  expectSameAsOriginal(in, "--position P.X,P.Y,P.Z --normal-space camera-gl");
  expectRefused(in, "--position P.X,P.Y,P.Z", "normal pass", "--normal-space camera-gl");
  // A camera whose field of view is 10% off: the depth-derived normals barely turn, but the
  // positions no longer land on their pixels.
  ssrcl::Camera narrower = s.camera;
  narrower.projection[0][0] *= 1.1;
  narrower.projection[1][1] *= 1.1;
  const std::string wrongCamera =
      variant("position-narrower",
              baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") + positions(s, "P.") +
                  cameraNormals(s, kBlender + "Normal.", "XYZ", kGlCamera),
              {}, &narrower);
  expectRefused(wrongCamera, "--position P.X,P.Y,P.Z --normal-space camera-gl", "does not land on its pixels",
                "--camera");
}

// A file with both positions and a depth pass: they must agree. World positions beside the depth
// trace as the original; eye-space positions written as P are refused, naming both passes.
TEST_P(Conventions, PositionsCheckedAgainstDepth) {
  const Sample& s = sample();
  const std::vector<ExrChannel> common = baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                                         std::vector<ExrChannel>{{kBlender + "Depth.Z", s.channel(s.g.depth, 0)}} +
                                         worldNormals(s, kBlender + "Normal.");
  expectSameAsOriginal(variant("p-and-z", common + positions(s, "P."), {}, &s.camera), "--position P.X,P.Y,P.Z");
  expectRefused(variant("eye-p-and-z", common + positions(s, "P.", true), {}, &s.camera), "--position P.X,P.Y,P.Z",
                "position pass disagrees with the depth pass", "--position");
}

// RenderMan's conventions: planar Z (its OpenEXR driver names output variable z "Z"), camera-space Nn
// (+z forward), worldToCamera + worldToNDC, clipNear + clipFar (used instead of fitted planes). A
// near plane beyond the nearest surface is not this render's camera: refused.
TEST_P(Conventions, RenderManPresetWithHeaderCamera) {
  const Sample& s = sample();
  const auto channels = baseChannels(s, "", "roughness") + std::vector<ExrChannel>{{"Z", s.channel(s.g.depth, 0)}} +
                        cameraNormals(s, "Nn.", "xyz", kExrCamera);
  double nearestSurface = INFINITY;
  for (int i = 0; i < s.w * s.h; ++i)
    if (!s.sky(i)) nearestSurface = std::min(nearestSurface, double(s.g.depth.data[i]));
  for (const double nearPlane : {s.camera.nearPlane, 2.0 * nearestSurface}) {
    ExrOptions options;
    options.editHeader = [&](Imf::Header& h) {
      addStandardCamera(h, s, Projected::StandardNdc, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
      addClipPlanes(h, "clipNear", "clipFar", nearPlane, s.camera.farPlane);
    };
    const bool right = nearPlane == s.camera.nearPlane;
    const std::string in = variant(right ? "renderman" : "renderman-near", channels, options);
    if (right) {
      expectSameAsOriginal(in, "--renderer renderman");
      expectRefused(in, "--renderer renderman --normal-space world", "normal pass", "--normal-space camera");
    } else {
      expectRefused(in, "--renderer renderman",
                    "renderman-near.exr: the header camera (worldToCamera + worldToNDC, clipNear + clipFar)", "--camera");
    }
  }
}

// Layouts a preset lists as alternatives (docs/renderers.md): Karma's colour and normals
// as Mantra names planes (N.x) and as a Houdini multi-part file holds them (parts C and N of
// channels R, G, B: OpenImageIO issue 3593; where the depth part's channel is named is not in that
// source, so depth is a bare `depth` here). Each reads to the original's pass; the multi-part
// file's bare R, in two parts, is never read as colour. RenderMan 26's layout as Gaffer's tests read
// it back (GafferHQ/gaffer python/IECoreRenderManTest/RendererTest.py, testEXRLayerNames: a colour
// output NAME is written NAME.r, NAME.g, NAME.b), here Ci without `asrgba` and Nn, with RenderMan for
// Blender's depth output name z_depth. (RenderMan's "Z|z": test_io, ChannelAlternatives.)
TEST_P(Conventions, PresetLayoutAlternatives) {
  if (std::string(GetParam()) != "mirror") GTEST_SKIP() << "channel layouts do not depend on the scene";
  const Sample& s = sample();
  ExrOptions houdini;
  houdini.editHeader = [&](Imf::Header& h) {
    addStandardCamera(h, s, Projected::Houdini, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
  };
  const std::vector<ExrChannel> depth = {{"depth", s.channel(s.g.depth, 0)}};
  expectSameAsOriginal(
      variant("mantra", baseChannels(s, "", "roughness") + depth + worldNormals(s, "N.", -1, "xyz"), houdini),
      "--renderer karma");

  const std::vector<ExrChannel> beauty = baseChannels(s, "", "roughness"), normals = worldNormals(s, "", -1, "RGB");
  const std::string parts = dir->file(s.name + ".houdini-parts.exr");
  ssrcl::test::writeMultiPartExr(parts, s.w, s.h, {{"C", beauty}, {"N", normals}, {"depth", depth}}, houdini);
  expectSameAsOriginal(parts, "--renderer karma");
  expectRefused(parts, "--renderer karma --color-channels R,G,B", "'R' is in 2 parts", "'C.R'");

  ExrOptions renderman;
  renderman.editHeader = [&](Imf::Header& h) {
    addStandardCamera(h, s, Projected::StandardNdc, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
  };
  expectSameAsOriginal(variant("renderman26",
                               baseChannels(s, "Ci.", "roughness", "rgb") +
                                   std::vector<ExrChannel>{{"z_depth", s.channel(s.g.depth, 0)}} +
                                   cameraNormals(s, "Nn.", "rgb", kExrCamera),
                               renderman),
                       "--renderer renderman");
}

// Arnold's, as its files hold them (ArnoldFileHeaderCamera): planar Z, world N, worldToCamera +
// worldToNDC in its [-1, 1] layout. The preset read Z as radial until Arnold's own files showed
// otherwise: that reading is refused.
TEST_P(Conventions, ArnoldPresetWithArnoldHeader) {
  const Sample& s = sample();
  const std::string in = arnoldNamedVariant("arnold", Projected::ArnoldNdc, s.channel(s.g.depth, 0), true);
  expectSameAsOriginal(in, "--renderer arnold");
  expectRefused(in, "--renderer arnold --depth-kind radial", "depth pass", "--depth-kind planar");
}

// Radial depth with worldToCamera + worldToScreen (OpenImageIO's screen space, as Arnold writes it
// through OpenImageIO 2.2 and later; the samples are 16:9, so an aspect-scaled reading fails).
TEST_P(Conventions, RadialDepthWithScreenMatrix) {
  const std::string in = arnoldNamedVariant("screen", Projected::Screen, radialDepth(sample()));
  expectSameAsOriginal(in, "--renderer arnold --depth-kind radial");
  expectRefused(in, "--renderer arnold", "depth pass", "--depth-kind radial");
}

// Houdini's header camera (HoudiniHeaderCamera) with a Blender-named G-buffer: told from the
// matrices, it reads as the render's camera.
TEST_P(Conventions, HoudiniHeaderLayout) {
  const Sample& s = sample();
  ExrOptions options;
  options.editHeader = [&](Imf::Header& h) {
    addStandardCamera(h, s, Projected::Houdini, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
  };
  expectSameAsOriginal(variant("houdini",
                               baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                                   std::vector<ExrChannel>{{kBlender + "Depth.Z", s.channel(s.g.depth, 0)}} +
                                   worldNormals(s, kBlender + "Normal."),
                               options),
                       "");
}

// V-Ray's: planar Z, camera-space normals (y down, +z forward, as V-Ray for Maya writes them:
// VrayFileNormals), cameraTransform + cameraFov.
TEST_P(Conventions, VrayPresetWithVrayCamera) {
  const Sample& s = sample();
  ExrOptions options;
  options.editHeader = [&](Imf::Header& h) { addVrayCamera(h, s); };
  const std::string in = variant("vray",
                                 baseChannels(s, "", "roughness") +
                                     std::vector<ExrChannel>{{"Z", s.channel(s.g.depth, 0)}} +
                                     cameraNormals(s, "normals.", "XYZ", kCvCamera),
                                 options);
  expectSameAsOriginal(in, "--renderer vray");
  expectRefused(in, "--renderer vray --normal-space camera-gl", "normal pass", "--normal-space camera-cv");
  // Normals as Chaos's docs describe them (y up, z toward the viewer): the preset is refused.
  const std::string documented = variant("vray-documented",
                                         baseChannels(s, "", "roughness") +
                                             std::vector<ExrChannel>{{"Z", s.channel(s.g.depth, 0)}} +
                                             cameraNormals(s, "normals.", "XYZ", kGlCamera),
                                         options);
  expectRefused(documented, "--renderer vray", "normal pass", "--normal-space camera-gl");
}

// The original frame as the overscan of a smaller display window: traced over all of it, the
// windows kept. And as a crop of a larger one.
TEST_P(Conventions, OverscanAndCrop) {
  const Sample& s = sample();
  const auto channels = baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                        std::vector<ExrChannel>{{kBlender + "Depth.Z", s.channel(s.g.depth, 0)}} +
                        worldNormals(s, kBlender + "Normal.");
  for (const Imath::Box2i display : {Imath::Box2i({30, 10}, {s.w - 51, s.h - 31}),     // overscan
                                     Imath::Box2i({-50, -40}, {s.w + 69, s.h + 39})}) {  // crop
    const ssrcl::Camera camera = cameraForWindow(s, display.min.x, display.min.y, display.max.x, display.max.y);
    // The window camera sees each world point at the same pixel, counted from its own corner.
    const glm::dvec3 p(0.3, -0.2, -5.0);
    const glm::dvec3 a = ssrcl::cameraToScreen(s.camera, p), b = ssrcl::cameraToScreen(camera, p);
    ASSERT_NEAR(b.x + display.min.x, a.x, 1e-9);
    ASSERT_NEAR(b.y + display.min.y, a.y, 1e-9);
    ExrOptions options;
    options.displayWindow = display;
    const std::string tag = display.min.x > 0 ? "overscan" : "crop";
    expectSameAsOriginal(variant(tag, channels, options, &camera), "", &display);
  }
}

// `ssrcl batch` reads frames the same way: an overscan frame whose only camera is its header's
// (for the display window), traced over its data window, windows kept.
TEST_P(Conventions, BatchOverscanWithHeaderCamera) {
  const Sample& s = sample();
  const Imath::Box2i display({20, 15}, {s.w - 41, s.h - 26});
  const ssrcl::Camera camera = cameraForWindow(s, display.min.x, display.min.y, display.max.x, display.max.y);
  ExrOptions options;
  options.displayWindow = display;
  options.editHeader = [&](Imf::Header& h) { addStandardCamera(h, s, Projected::StandardNdc, camera, display); };
  const std::string in = variant("batch", baseChannels(s, "", "roughness") +
                                              std::vector<ExrChannel>{{"Z", s.channel(s.g.depth, 0)}} +
                                              cameraNormals(s, "Nn.", "xyz", kExrCamera),
                                 options);
  const std::string outDir = dir->file(s.name + ".batch.out");
  const auto r = runCommand(cli("batch " + shellQuote(in) + " --renderer renderman -q -o " + shellQuote(outDir + "/")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectSameAs(outDir + "/" + s.name + ".batch.refl.exr", &display);
}

// Declarations that contradict the passes, on the untouched sample.
TEST_P(Conventions, WrongDeclarationsAreRefused) {
  const Sample& s = sample();
  const std::string in = samplePath(s.name, ".exr");
  const std::string camera = "--camera " + shellQuote(samplePath(s.name, ".camera.json"));
  expectRefused(in, camera + " --normal-space camera", "normal pass", "--normal-space world");
  expectRefused(in, camera + " --depth-kind radial", "depth pass", "--depth-kind planar");
  expectRefused(in, camera + " --renderer vray --layer ViewLayer --color-channels '' --depth-channel '' "
                             "--normal-channels ''",
                "normal pass", "--normal-space world");

  const std::string flipped = variant("flipped",
                                      baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                                          std::vector<ExrChannel>{{kBlender + "Depth.Z", s.channel(s.g.depth, 0)}} +
                                          worldNormals(s, kBlender + "Normal.", 1),
                                      {}, &s.camera);
  expectRefused(flipped, "", "normal pass's y axis", "--no-input-check");

  // A camera that is not the render's: rolled a quarter turn about its axis.
  ssrcl::Camera rolled = s.camera;
  rolled.view = glm::rotate(glm::dmat4(1.0), M_PI / 2, glm::dvec3(0, 0, 1)) * s.camera.view;
  const std::string rolledPath = dir->file(s.name + ".rolled.camera.json");
  ssrcl::saveCameraJson(rolledPath, rolled);
  expectRefused(in, "--camera " + shellQuote(rolledPath), "camera", "--no-input-check");
}

// The check's margins on the untouched sample, declared rightly: every other reading that tells
// the passes apart puts the pass normals far from where they are (score near -1; refusal takes
// above +0.5), and the declared reading fits within a couple of degrees.
TEST_P(Conventions, CheckSeparatesReadings) {
  const Sample& s = sample();
  ssrcl::GBufferSource source;
  source.file = samplePath(s.name, ".exr");
  const ssrcl::InputCheckReport report = ssrcl::checkInputConventions(s.g, source, s.camera);
  EXPECT_EQ(report.preferred.depth, "planar");
  EXPECT_EQ(report.preferred.normals, "world");
  EXPECT_LT(report.declared.meanAngleDegrees, 2.0);
  EXPECT_GT(report.comparedPixels, 10000);
  for (const ssrcl::ConventionFit& r : report.readings) {
    RecordProperty(r.depth + " depth, " + r.normals + " normals",
                   std::to_string(r.meanAngleDegrees) + " deg, score " + std::to_string(r.score));
    if (r.depth == "planar" && r.normals == "world") continue;
    if (r.meanAngleDegrees - report.declared.meanAngleDegrees > 3.0) EXPECT_LT(r.score, -0.5) << r.depth << " " << r.normals;
  }
}

// Without a sidecar, a header without a camera, or with one that cannot be used, is refused with
// the file and attribute named; a sidecar still wins over an unusable header camera.
TEST_P(Conventions, HeaderCameraMissingOrUnusable) {
  const Sample& s = sample();
  const auto channels = baseChannels(s, kBlender + "Combined.", kBlender + "roughness.X") +
                        std::vector<ExrChannel>{{kBlender + "Depth.Z", s.channel(s.g.depth, 0)}} +
                        worldNormals(s, kBlender + "Normal.");
  expectRefused(variant("nocamera", channels), "", "has no camera in its header", "--camera");
  ExrOptions options;
  options.editHeader = [&](Imf::Header& h) {
    h.insert("cameraTransform", Imf::M44fAttribute(imath(glm::inverse(s.camera.view))));
    h.insert("cameraFov", Imf::FloatAttribute(60.0f));
    h.insert("cameraProjection", Imf::IntAttribute(2));  // spherical
  };
  const std::string unusable = variant("spherical", channels, options);
  expectRefused(unusable, "", "'cameraProjection'", "--camera");
  const auto r = runCommand(cli("trace " + shellQuote(unusable) + " --camera " +
                                shellQuote(samplePath(s.name, ".camera.json")) + " --max-roughness 0 -o " +
                                shellQuote(unusable + ".refl.exr")));
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

// Karma's layout (KarmaHeaderCamera): its channels, world normals, worldToCamera with +z forward and
// a worldToNDC that copies it. --fov, the sample camera's, completes the camera: the original's
// pass. Without it, or with it beside a camera file, or beside a header that has no camera, or one
// whose own projection it contradicts: refused, naming what to give.
TEST_P(Conventions, KarmaHeaderWithFieldOfView) {
  const Sample& s = sample();
  ASSERT_EQ(s.camera.projection[2][0], 0.0) << "a centred frustum, which a field of view describes";
  const double fov = 2.0 * std::atan(1.0 / s.camera.projection[0][0]) * 180.0 / M_PI;
  const auto fovOption = [](double degrees) {
    char text[48];
    std::snprintf(text, sizeof text, "--fov %.9g", degrees);
    return std::string(text);
  };
  const auto channels = baseChannels(s, "", "roughness") +
                        std::vector<ExrChannel>{{"depth", s.channel(s.g.depth, 0)}} + worldNormals(s, "N.", -1, "xyz");
  ExrOptions karma;
  karma.editHeader = [&](Imf::Header& h) {
    const Imath::M44f toCamera = imath(glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, -1)) * s.camera.view);
    h.insert("worldToCamera", Imf::M44fAttribute(toCamera));
    h.insert("worldToNDC", Imf::M44fAttribute(toCamera));
  };
  const std::string in = variant("karma", channels, karma);
  expectSameAsOriginal(in, "--renderer karma " + fovOption(fov));
  expectRefused(in, "--renderer karma", "'worldToNDC' is the same matrix as 'worldToCamera'", "give --fov");
  expectRefused(in, "--renderer karma --camera " + shellQuote(samplePath(s.name, ".camera.json")) + " " +
                        fovOption(fov),
                "--fov completes a header camera, but the camera comes from", "drop --fov");
  expectRefused(variant("karma-nocamera", channels), "--renderer karma " + fovOption(fov),
                "has no worldToCamera in its header for --fov to complete", "give --camera");
  ExrOptions standard;
  standard.editHeader = [&](Imf::Header& h) {
    addStandardCamera(h, s, Projected::StandardNdc, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
  };
  expectRefused(variant("karma-projected", channels, standard), "--renderer karma " + fovOption(fov + 1.0),
                "karma-projected.exr: the header camera (worldToCamera + worldToNDC) has a horizontal field of view",
                "says otherwise: drop --fov");
}

// Karma's layout with a world-position pass instead of depth: the field of view is fitted to the
// positions (to 1e-4 of the sample camera's focal length) and traces to the original's pass, named
// in ssrcl/inputs. The input check cannot catch a wrong --fov from depth and normals (the mean
// angle between the normal pass and depth-derived normals grows from 1.0 to 2.2 degrees at 10% off,
// 8 degrees at half or twice the focal length, every other reading still worse); the positions
// can: a --fov 10% off is refused, and so is a pose the positions do not fit.
TEST_P(Conventions, KarmaFieldOfViewFromPositions) {
  const Sample& s = sample();
  const auto channels = baseChannels(s, "", "roughness") + positions(s, "P.") + worldNormals(s, "N.", -1, "xyz");
  const auto karmaHeader = [&](const glm::dmat4& view) {
    ExrOptions karma;
    karma.editHeader = [view](Imf::Header& h) {
      const Imath::M44f toCamera = imath(glm::scale(glm::dmat4(1.0), glm::dvec3(1, 1, -1)) * view);
      h.insert("worldToCamera", Imf::M44fAttribute(toCamera));
      h.insert("worldToNDC", Imf::M44fAttribute(toCamera));
    };
    return karma;
  };
  const std::string in = variant("karma-p", channels, karmaHeader(s.camera.view));

  ssrcl::GBufferSource source;
  source.file = in;
  source.layer = "";
  source.positionChannels = "P.X,P.Y,P.Z";
  source.normalChannels = "N.x,N.y,N.z";
  const ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
  ssrcl::HeaderCamera fitted = g.headerCamera.value();
  ssrcl::fitFieldOfView(fitted, g, in);
  EXPECT_NEAR(fitted.camera.projection[0][0] / s.camera.projection[0][0], 1.0, 1e-4);
  EXPECT_NEAR(fitted.camera.projection[1][1] / s.camera.projection[1][1], 1.0, 1e-4);
  RecordProperty("fitted", fitted.attributes);

  const std::string out = in + ".refl.exr";
  const auto r = runCommand(cli("trace " + shellQuote(in) + " --renderer karma --position P.X,P.Y,P.Z -o " +
                                shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectSameAs(out, nullptr);
  const std::string inputs = ssrcl::test::stringAttribute(out, "ssrcl/inputs");
  EXPECT_NE(inputs.find("worldToCamera + field of view "), std::string::npos) << inputs;
  EXPECT_NE(inputs.find(" fitted to the positions (median "), std::string::npos) << inputs;

  const double fov = 2.0 * std::atan(1.0 / s.camera.projection[0][0]) * 180.0 / M_PI;
  expectRefused(in, "--renderer karma --position P.X,P.Y,P.Z --fov " + std::to_string(1.1 * fov),
                "does not land on its pixels", "--fov");
  const glm::dmat4 turned = glm::rotate(glm::dmat4(1.0), 0.1, glm::dvec3(0, 0, 1)) * s.camera.view;
  expectRefused(variant("karma-p-turned", channels, karmaHeader(turned)), "--renderer karma --position P.X,P.Y,P.Z",
                "karma-p-turned.exr: the world positions do not fit the header camera's pose", "give --camera");
}

TEST_P(Conventions, NoInputCheckTracesAnyway) {
  const Sample& s = sample();
  const std::string out = dir->file(s.name + ".unchecked.exr");
  const auto r = runCommand(cli("trace " + shellQuote(samplePath(s.name, ".exr")) +
                                " --normal-space camera --no-input-check --roughness 1 --max-roughness 0 -o " +
                                shellQuote(out)));
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

INSTANTIATE_TEST_SUITE_P(BlenderSamples, Conventions, testing::Values("mirror", "glossy"));

// The corpus scenes (bump-mapped floors, thin objects, grazing views, centimetre units): no false
// alarm when declared rightly, and each wrong declaration still refused. Check only, no tracing.
TEST(ConventionCheck, CorpusScenes) {
  const std::filesystem::path corpus = std::filesystem::path(SSRCL_SOURCE_DIR) / "samples" / "corpus";
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().stem().string();
    // EEVEE's renders and the back-face depth passes are no G-buffers.
    if (entry.path().extension() != ".exr" || name.find(".eevee") != std::string::npos ||
        name.find(".back") != std::string::npos)
      continue;
    ++scenes;
    ssrcl::GBufferSource source;
    source.file = entry.path().string();
    const ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
    const ssrcl::Camera camera = ssrcl::loadCameraJson((corpus / (name + ".camera.json")).string());
    const ssrcl::InputCheckReport right = ssrcl::checkInputConventions(g, source, camera);
    EXPECT_EQ(right.preferred.depth + " " + right.preferred.normals, "planar world") << name;
    std::string figures = "right " + std::to_string(right.declared.meanAngleDegrees) + " deg";
    for (const auto& [depth, space] : {std::pair{ssrcl::DepthKind::Radial, ssrcl::NormalSpace::World},
                                      std::pair{ssrcl::DepthKind::Planar, ssrcl::NormalSpace::Camera},
                                      std::pair{ssrcl::DepthKind::Planar, ssrcl::NormalSpace::CameraGL}}) {
      ssrcl::GBufferSource wrong = source;
      wrong.depthKind = depth;
      wrong.normalSpace = space;
      try {
        ssrcl::checkInputConventions(g, wrong, camera);
        ADD_FAILURE() << name << ": " << ssrcl::depthKindName(depth) << " " << ssrcl::normalSpaceName(space)
                      << " was not refused";
      } catch (const ssrcl::Error& e) {
        EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidInput);
        const std::string what = e.what();
        figures += std::string("; ") + ssrcl::depthKindName(depth) + "/" + ssrcl::normalSpaceName(space) + ": " +
                   what.substr(what.find("differ"));
      }
    }
    RecordProperty(name, figures);
  }
  if (scenes == 0) GTEST_SKIP() << "no corpus scenes in " << corpus;
}

// Orthographic header cameras: without a perspective divide, worldToCamera + worldToNDC read the
// same whether the file's camera looks down its +z (OpenEXR) or -z (Houdini), and the passes
// decide. The bundled samples are perspective renders, so the frame is an analytic orthographic
// one (scenes/analytic_scene.hpp) traced with its camera as a sidecar: the same passes with the
// camera in the header, in either layout, trace to that pass; frames that cannot tell are refused.
TEST(OrthographicHeaderCamera, PassesDecideWhichWayItLooks) {
  ssrcl::test::TempDir dir("ssrcl-ortho-header");
  const ssrcl::scenes::Scene scene = ssrcl::scenes::makeScene("spheres_on_mirror");
  Sample s;
  s.camera = ssrcl::scenes::makeCamera(scene.view, 160, 90);
  s.camera.projection = glm::ortho(-8.0, 8.0, -4.5, 4.5, 0.1, 1000.0);
  s.camera.nearPlane = 0.1;
  s.camera.farPlane = 1000.0;
  s.g = ssrcl::scenes::renderGBuffer(scene, s.camera);
  s.w = s.camera.width;
  s.h = s.camera.height;
  const auto plain = baseChannels(s, "", "roughness") + std::vector<ExrChannel>{{"Z", s.channel(s.g.depth, 0)}};
  const auto write = [&](const std::string& tag, const std::vector<ExrChannel>& channels, Projected layout,
                         double clipFar = 0.0) {
    ExrOptions options;
    options.editHeader = [&](Imf::Header& h) {
      addStandardCamera(h, s, layout, s.camera, Imath::Box2i({0, 0}, {s.w - 1, s.h - 1}));
      if (clipFar > 0.0) addClipPlanes(h, "clipNear", "clipFar", s.camera.nearPlane, clipFar);
    };
    const std::string path = dir.file(tag + ".exr");
    ssrcl::test::writeExr(path, s.w, s.h, channels, options);
    return path;
  };
  const std::string reference = dir.file("sidecar.exr"), referencePass = dir.file("sidecar.refl.exr");
  ssrcl::test::writeExr(reference, s.w, s.h, plain + worldNormals(s, "N."));
  ssrcl::saveCameraJson(dir.file("sidecar.camera.json"), s.camera);
  const auto r = runCommand(cli("trace " + shellQuote(reference) + " --layer '' -o " + shellQuote(referencePass)));
  ASSERT_EQ(r.exitCode, 0) << r.output;

  const auto expectTraced = [&](const std::string& input, const std::string& options, const std::string& looking) {
    const std::string out = input + ".refl.exr";
    const auto t = runCommand(cli("trace " + shellQuote(input) + " --layer '' " + options + " -o " + shellQuote(out)));
    ASSERT_EQ(t.exitCode, 0) << t.output;
    expectSamePass(referencePass, out);
    const std::string inputs = ssrcl::test::stringAttribute(out, "ssrcl/inputs");
    EXPECT_NE(inputs.find(looking), std::string::npos) << inputs;
    RecordProperty(std::filesystem::path(input).stem().string(), inputs);
  };
  // World normals decide (they face the camera), or positions do (they lie in front of it).
  expectTraced(write("exr-normals", plain + worldNormals(s, "N."), Projected::StandardNdc), "", "looking down +z");
  expectTraced(write("houdini-normals", plain + worldNormals(s, "N."), Projected::Houdini), "", "looking down -z");
  // Header clip planes hold for the reading the passes choose; an infinite far plane (RenderMan's
  // default 1e38) leaves the orthographic depth row, which has no infinite form, to the depth pass.
  expectTraced(write("houdini-clipped", plain + worldNormals(s, "N."), Projected::Houdini, s.camera.farPlane), "",
               "looking down -z");
  expectTraced(write("houdini-far-1e38", plain + worldNormals(s, "N."), Projected::Houdini, 1e38), "",
               "looking down -z");
  const auto cameraSpace =
      baseChannels(s, "", "roughness") + positions(s, "P.") + cameraNormals(s, "N.", "XYZ", kGlCamera);
  expectTraced(write("houdini-positions", cameraSpace, Projected::Houdini),
               "--position P.X,P.Y,P.Z --normal-space camera-gl", "looking down -z");
  expectTraced(write("exr-positions", cameraSpace, Projected::StandardNdc),
               "--position P.X,P.Y,P.Z --normal-space camera-gl", "looking down +z");

  // Camera-space normals without positions cannot tell; nor can normals half of which face away.
  expectRefused(write("camera-normals", plain + cameraNormals(s, "N.", "XYZ", kGlCamera), Projected::Houdini),
                "--layer '' --normal-space camera-gl", "is orthographic", "cannot tell either; give --camera");
  std::vector<ExrChannel> halfAway = worldNormals(s, "N.");
  for (int i = 0; i < s.w * s.h; i += 2)
    for (ExrChannel& c : halfAway) c.values[i] = -c.values[i];
  expectRefused(write("half-away", plain + halfAway, Projected::StandardNdc), "--layer ''", "is orthographic",
                "the frame does not tell either");
}

// A header exactly as Arnold 4.2 (MtoA) wrote it: github.com/zewt/exrflatten, sample/sample2.exr
// (deep scan lines, 500x500, channels R G B A Z ZBack N.X N.Y N.Z P.X P.Y P.Z id; matrices, clip
// planes and samples below copied from the file). Its Z is planar depth (within 1.4e-4 of the camera-space z
// of its world positions P over 455 sampled pixels; radial distance is 2.1% off) and its
// worldToNDC puts P on its pixel in [-1, 1], y up: the camera we read must do the same.
TEST(ArnoldFileHeaderCamera, PutsThePositionsOnTheirPixels) {
  Imf::Header header(500, 500);
  header.insert("arnold/version", Imf::StringAttribute("Arnold 4.2.16.2 windows icc-14.0.2 oiio-1.7.7 rlm-12.0.2"));
  header.insert("worldToCamera", Imf::M44fAttribute(Imath::M44f(-0.998239875f, -0.00345354597f, -0.0592057407f, 0,  //
                                                                0, 0.998303115f, -0.0582322925f, 0,                  //
                                                                -0.0593063794f, 0.0581297912f, 0.99654597f, 0,      //
                                                                -1.39829028f, -4.14148045f, 15.7246094f, 1)));
  header.insert("worldToNDC", Imf::M44fAttribute(Imath::M44f(-1.94102204f, -0.00671522878f, -0.059206333f, -0.0592057407f,
                                                             0, 1.94114506f, -0.0582328774f, -0.0582322925f,  //
                                                             -0.115317963f, 0.113030158f, 0.996555924f, 0.99654597f,
                                                             -2.71889782f, -8.05287933f, 14.7247562f, 15.7246094f)));
  struct Sampled {
    glm::dvec3 p;  // P (stored as half)
    int x, y;      // its pixel
    double z;      // Z
  };
  const Sampled samples[] = {{{1.626953, 6.492188, -5.800781}, 112, 147, 9.469747},
                             {{-1.246094, 5.835938, -0.2224121}, 245, 196, 15.23683},
                             {{-1.359375, 4.996094, -6.097656}, 266, 224, 9.43747},
                             {{0.7294922, 3.873047, 3.142578}, 189, 252, 18.58721},
                             {{-2.449219, 4.371094, -9.265625}, 371, 273, 6.382986}};
  header.insert("arnold/camera/near_clip", Imf::FloatAttribute(1.0f));
  header.insert("arnold/camera/far_clip", Imf::FloatAttribute(100000.0f));
  // They are this camera's planes: the file's own worldToNDC z column holds f (z - n) / (f - n).
  const Imath::M44f& toNdc = header.typedAttribute<Imf::M44fAttribute>("worldToNDC").value();
  for (int row = 0; row < 4; ++row)
    EXPECT_NEAR(toNdc[row][2], (toNdc[row][3] - (row == 3 ? 1.0 : 0.0)) * 100000.0 / 99999.0, 1e-5) << row;
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "sample2.exr");
  ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
  EXPECT_TRUE(read->clipPlanesKnown);
  EXPECT_DOUBLE_EQ(read->camera.nearPlane, 1.0);
  EXPECT_DOUBLE_EQ(read->camera.farPlane, 100000.0);
  for (const Sampled& sample : samples) {
    const glm::dvec3 eye = glm::dvec3(read->camera.view * glm::dvec4(sample.p, 1.0));
    const glm::dvec3 screen = ssrcl::cameraToScreen(read->camera, eye);
    // P is stored as half: a few thousandths of a unit, a few tenths of a pixel at this distance.
    EXPECT_NEAR(screen.x, sample.x + 0.5, 0.3) << sample.x << "," << sample.y;
    EXPECT_NEAR(screen.y, sample.y + 0.5, 0.3) << sample.x << "," << sample.y;
    EXPECT_NEAR(screen.z, sample.z, 2e-3 * sample.z) << "planar depth";
  }

  // Read as OpenEXR's [0, 1] NDC, as the attribute's name says, the same matrices would put P
  // far from its pixel: x' = 2x - w, y' = w - 2y on the file's own projection.
  const Imath::M44f& m = header.typedAttribute<Imf::M44fAttribute>("worldToNDC").value();
  Imath::V3f misread;
  m.multVecMatrix(Imath::V3f(float(samples[0].p.x), float(samples[0].p.y), float(samples[0].p.z)), misread);
  EXPECT_GT(std::abs(misread.x * 500.0 - (samples[0].x + 0.5)), 50.0);
}

// A header camera `read` from a file whose worldToCamera is `toCamera` (OpenEXR camera space, +z
// forward) and whose horizontal field of view is `fovDegrees` (the file's own CameraFov, written
// beside the matrices): points down the camera's +z axis fall on the frame's centre at their
// planar depth, and the frame's right and top edges lie at that field of view.
void expectCameraOfFov(const ssrcl::HeaderCamera& read, const Imath::M44f& toCamera, double fovDegrees, int width,
                       int height) {
  const Imath::M44f toWorld = toCamera.inverse();
  const double t = std::tan(fovDegrees * M_PI / 360.0);
  const auto screen = [&](double x, double y, double z) {
    Imath::V3f world;
    toWorld.multVecMatrix(Imath::V3f(float(x), float(y), float(z)), world);
    const glm::dvec4 p(world.x, world.y, world.z, 1.0);
    return ssrcl::cameraToScreen(read.camera, glm::dvec3(read.camera.view * p));
  };
  for (const double d : {1.0, 10.0}) {
    const glm::dvec3 centre = screen(0.0, 0.0, d);
    EXPECT_NEAR(centre.x, width / 2.0, 1e-2 * width) << d;
    EXPECT_NEAR(centre.y, height / 2.0, 1e-2 * height) << d;
    EXPECT_NEAR(centre.z, d, 1e-3 * d) << "planar depth";
    EXPECT_NEAR(screen(d * t, 0.0, d).x, width, 1e-2 * width) << "right edge";
    EXPECT_NEAR(screen(0.0, d * t * height / width, d).y, 0.0, 1e-2 * height) << "top edge";
  }
}

// Arnold 5 and 7 headers as their files hold them. Arnold writes through OpenImageIO: 5.4.0
// (oiio-2.1.0) a screen-space worldToNDC, 7.1.3 (oiio-2.4.1) and 7.4.2.1 (oiio-2.6.3) the same
// matrix as worldToScreen; all look down +z, with CameraFov (horizontal, degrees) and
// arnold/camera/near_clip, far_clip beside them. Matrices copied from: Gaffer's
// python/GafferImageTest/images/representativeDeepImage.exr (150x100) and arnoldCombinedID.exr
// (16x16, github.com/GafferHQ/gaffer), and test/images/arnold_three_crypto.exr (320x180,
// github.com/EmilDohne/cryptomatte-api).
TEST(ArnoldFileHeaderCamera, Arnold5And7HeadersReadAsTheirCameras) {
  struct File {
    const char* name;
    const char* version;
    int width, height;
    Imath::M44f toCamera, projected;
    const char* projectedName;
    float fov, nearClip, farClip;
  };
  const File files[] = {
      {"representativeDeepImage.exr", "Arnold 5.4.0.0 [b7d9819c] linux clang-5.0.0 oiio-2.1.0", 150, 100,
       Imath::M44f(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 7.2625f, 1),
       Imath::M44f(2.14451f, 0, 0, 0, 0, 3.21676f, 0, 0, 0, 0, -1, -1, 0, 0, 7.2525f, 7.2625f), "worldToNDC", 50.0f,
       0.01f, 100000.0f},
      {"arnoldCombinedID.exr", "Arnold 7.4.2.1 [37ff9861] linux x86_64 clang-15.0.7 oiio-2.6.3", 16, 16,
       Imath::M44f(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 2.18629f, 1),
       Imath::M44f(2.14451f, 0, 0, 0, 0, 2.14451f, 0, 0, 0, 0, -1, -1, 0, 0, 2.17629f, 2.18629f), "worldToScreen",
       50.0f, 0.01f, 100000.0f},
      {"arnold_three_crypto.exr", "Arnold 7.1.3.0 [a8020120] windows clang-10.0.1 oiio-2.4.1", 320, 180,
       Imath::M44f(0.622515f, 0.487185f, 0.612476f, 0, -0.782608f, 0.387525f, 0.487185f, 0, 1.34111e-07f, 0.782609f,
                   -0.622515f, 0, 5.26391f, 6.17814f, 508.484f, 1),
       Imath::M44f(1.488f, 2.07026f, 0.612476f, 0.612476f, -1.87068f, 1.64676f, 0.487185f, 0.487185f, 3.20566e-07f,
                   3.32565f, -0.622515f, -0.622515f, 12.5824f, 26.2537f, 508.484f, 508.484f),
       "worldToScreen", 45.4045f, 0.0001f, 1e12f},
  };
  for (const File& f : files) {
    SCOPED_TRACE(f.name);
    for (int row = 0; row < 4; ++row) EXPECT_NEAR(f.projected[row][3], f.toCamera[row][2], 1e-4) << "w = +z";
    Imf::Header header(f.width, f.height);
    header.insert("arnold/version", Imf::StringAttribute(f.version));
    header.insert("worldToCamera", Imf::M44fAttribute(f.toCamera));
    header.insert(f.projectedName, Imf::M44fAttribute(f.projected));
    header.insert("CameraFov", Imf::FloatAttribute(f.fov));
    addClipPlanes(header, "arnold/camera/near_clip", "arnold/camera/far_clip", f.nearClip, f.farClip);
    const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, f.name);
    ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
    EXPECT_FALSE(read->reversed) << "perspective: the divide tells the camera's axis";
    EXPECT_TRUE(read->clipPlanesKnown);
    EXPECT_FLOAT_EQ(float(read->camera.nearPlane), f.nearClip);
    expectCameraOfFov(*read, f.toCamera, f.fov, f.width, f.height);
  }
}

// Karma's header (Houdini Solaris; Karma CPU and XPU write the same): worldToCamera in OpenEXR's
// camera space (+z forward: the scene's origin, 37.9 units away, lies on its +z side) and a
// worldToNDC that is a copy of it, holding no projection. Read as the pose alone, never as an
// orthographic camera: unusable (naming the attribute, --fov and --camera) until a field of view
// completes it, then the camera of that field of view. From github.com/EmilDohne/cryptomatte-api
// test/images/karma_cpu_solaris_one_crypto.exr (140x79).
TEST(KarmaHeaderCamera, WorldToNdcWithoutProjectionTakesAFieldOfView) {
  const Imath::M44f toCamera(0.674045f, 0.4127f, 0.612652f, 0, 1.49012e-08f, 0.829375f, -0.558692f, 0,  //
                             0.738691f, -0.376583f, -0.559036f, 0, 0.290508f, 1.13962f, 37.8625f, 1);
  Imath::V3f origin;
  toCamera.multVecMatrix(Imath::V3f(0, 0, 0), origin);
  EXPECT_GT(origin.z, 37.0f) << "+z forward";
  Imf::Header header(140, 79);
  header.insert("worldToCamera", Imf::M44fAttribute(toCamera));
  header.insert("worldToNDC", Imf::M44fAttribute(toCamera));
  std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "karma.exr");
  ASSERT_TRUE(read);
  EXPECT_EQ(read->problem, "");
  EXPECT_FALSE(read->reversed);
  EXPECT_NE(read->unprojected.find("karma.exr: header attribute 'worldToNDC' is the same matrix as 'worldToCamera'"),
            std::string::npos)
      << read->unprojected;
  EXPECT_NE(read->unprojected.find("--fov"), std::string::npos) << read->unprojected;
  EXPECT_NE(read->unprojected.find("--camera"), std::string::npos) << read->unprojected;
  ssrcl::applyFieldOfView(*read, 39.6, "karma.exr");
  EXPECT_EQ(read->unprojected, "");
  EXPECT_EQ(read->attributes, "worldToCamera + --fov 39.6");
  expectCameraOfFov(*read, toCamera, 39.6, 140, 79);
  // Clip planes in the header survive the completion.
  header.insert("clipNear", Imf::FloatAttribute(0.01f));
  header.insert("clipFar", Imf::FloatAttribute(1000.0f));
  std::optional<ssrcl::HeaderCamera> clipped = ssrcl::detail::cameraFromHeader(header, "karma.exr");
  ASSERT_TRUE(clipped && clipped->problem.empty() && clipped->clipPlanesKnown);
  ssrcl::applyFieldOfView(*clipped, 39.6, "karma.exr");
  EXPECT_NEAR(clipped->camera.nearPlane, 0.01, 1e-8);
  EXPECT_NEAR(clipped->camera.farPlane, 1000.0, 1e-4);
  expectCameraOfFov(*clipped, toCamera, 39.6, 140, 79);
  // Once it has a projection, a field of view is a check: within 0.1 degree, else refused.
  EXPECT_NO_THROW(ssrcl::applyFieldOfView(*read, 39.65, "karma.exr"));
  try {
    ssrcl::applyFieldOfView(*read, 39.8, "karma.exr");
    ADD_FAILURE() << "a field of view 0.2 degree off was taken";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(std::string(e.what()), "karma.exr: the header camera (worldToCamera + --fov 39.6) has a horizontal "
                                     "field of view of 39.6 degrees but --fov 39.8 says otherwise: drop --fov or "
                                     "correct it");
  }
  for (const double fov : {0.0, 180.0, -5.0, double(NAN)}) {
    ssrcl::HeaderCamera unprojected = *ssrcl::detail::cameraFromHeader(header, "karma.exr");
    EXPECT_THROW(ssrcl::applyFieldOfView(unprojected, fov, "karma.exr"), ssrcl::Error) << fov;
  }
}

// V-Ray's cameraTransform frame, from two V-Ray files. A V-Ray for Maya 3.60.05 header (Psyop/Cryptomatte
// sample_images/cornellBox_CryptoWildcard.0001.exr, 960x540 display window, a crop data window):
// Maya's front view at (0, 5, 20), looking down world -z with y up, stored as rows (1 0 0, 0 0 1,
// 0 -1 0): the camera looks down the matrix's -y with -z up. Its cameraFov is the horizontal angle
// of its own aperture and focal length: 2 atan(35.9999 / (2 * 35)).
TEST(VrayFileHeaderCamera, MayaFrontViewReadsAsItsCamera) {
  Imf::Header header(Imath::Box2i({0, 0}, {959, 539}), Imath::Box2i({167, 0}, {792, 539}));
  header.insert("cameraTransform", Imf::M44fAttribute(Imath::M44f(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 5, 20, 1)));
  header.insert("cameraFov", Imf::FloatAttribute(54.4322f));
  header.insert("cameraAperture", Imf::FloatAttribute(35.9999f));
  header.insert("cameraFocalLength", Imf::FloatAttribute(35.0f));
  header.insert("cameraProjection", Imf::IntAttribute(0));
  header.insert("cameraNearClip", Imf::FloatAttribute(0.0f));
  header.insert("cameraFarClip", Imf::FloatAttribute(1e30f));
  EXPECT_NEAR(2.0 * std::atan(35.9999 / (2.0 * 35.0)) * 180.0 / M_PI, 54.4322, 1e-3);
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "cornellBox.exr");
  ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
  EXPECT_FALSE(read->clipPlanesKnown) << "cameraNearClip 0 is not a range";
  const auto screen = [&](double x, double y, double z) {
    return ssrcl::cameraToScreen(read->camera, glm::dvec3(read->camera.view * glm::dvec4(x, y, z, 1.0)));
  };
  const double t = std::tan(54.4322 * M_PI / 360.0);
  for (const double d : {2.0, 20.0}) {
    const glm::dvec3 centre = screen(0.0, 5.0, 20.0 - d);
    EXPECT_NEAR(centre.x, 480.0, 1e-3) << d;
    EXPECT_NEAR(centre.y, 270.0, 1e-3) << d;
    EXPECT_NEAR(centre.z, d, 1e-4 * d) << "planar depth";
    EXPECT_NEAR(screen(d * t, 5.0, 20.0 - d).x, 960.0, 0.05) << "right edge, world +x";
    EXPECT_NEAR(screen(0.0, 5.0 + d * t * 540.0 / 960.0, 20.0 - d).y, 0.0, 0.05) << "top edge, world +y";
  }
}

// A field of view spans the width; with non-square pixels the height would come out wrong, so V-Ray's
// cameraFov and Karma's pose-only header are refused for them (the matrices' own cameras carry it).
TEST(HeaderCameraFromFieldOfView, NonSquarePixelsAreRefused) {
  Imf::Header vray(960, 540, 2.0f);
  vray.insert("cameraTransform", Imf::M44fAttribute(Imath::M44f(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 5, 20, 1)));
  vray.insert("cameraFov", Imf::FloatAttribute(54.4322f));
  Imf::Header karma(140, 79, 2.0f);
  const Imath::M44f pose(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 10, 1);
  karma.insert("worldToCamera", Imf::M44fAttribute(pose));
  karma.insert("worldToNDC", Imf::M44fAttribute(pose));
  for (const auto& [header, name] : {std::pair{&vray, "vray.exr"}, std::pair{&karma, "karma.exr"}}) {
    const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(*header, name);
    ASSERT_TRUE(read) << name;
    EXPECT_NE(read->problem.find(std::string(name) + ": pixelAspectRatio is 2"), std::string::npos) << read->problem;
    EXPECT_NE(read->problem.find("--camera"), std::string::npos) << read->problem;
  }
}

// The other: a V-Ray 3.60.04 render of a z-up scene (Andrew Hazelden's Altus Denoiser sample passes
// in the Reactor package, mirrored at github.com/wtxszyez/1123: Atoms/com.AndrewHazelden.AltusDenoiserUltra/
// Comps/AltusDenoiser/Media/altus_input/WorldPositions_b0.0001.exr, 1920x800, its header rewritten by
// Fusion: cameraProjection a float). Read so, all 1536000 of its world positions lie in front of the
// camera and 99.9% of its world normals face it; those near the frame's centre, sampled below (P
// stored as half), land within 2 pixels of their own. Toward the edges they drift, up to tens of
// pixels (the render's physical camera is no exact pinhole: its cameraFocalLength 32.8 disagrees
// with its cameraFov), so only the centre is held to its pixels.
TEST(VrayFileHeaderCamera, WorldPositionsNearTheCentreLandOnTheirPixels) {
  Imf::Header header(1920, 800);
  header.insert("cameraTransform", Imf::M44fAttribute(Imath::M44f(0.999082f, 0, -0.0428318f, 0,                //
                                                                  0.0423335f, -0.152098f, 0.987458f, 0,         //
                                                                  -0.00651465f, -0.988365f, -0.151959f, 0,      //
                                                                  8.95973f, -28.4696f, 276.68f, 1)));
  header.insert("cameraFov", Imf::FloatAttribute(54.432f));
  header.insert("cameraProjection", Imf::FloatAttribute(0.0f));
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "WorldPositions_b0.exr");
  ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
  struct Sampled {
    glm::dvec3 p;
    int x, y;
  };
  const Sampled samples[] = {{{1.291016, -0.5717773, 94.8125}, 960, 400}, {{-20.15625, 18.57812, 51.9375}, 800, 300},
                             {{19.0625, -5.074219, 41}, 1120, 500},       {{-5.5, -11.5, 106.25}, 880, 500},
                             {{9.195312, 15.48438, 65.4375}, 1040, 300},  {{0.3007812, 19.95312, 71.625}, 960, 250},
                             {{1.494141, -15.57031, 99.5625}, 960, 550}};
  for (const Sampled& sample : samples) {
    const glm::dvec3 eye = glm::dvec3(read->camera.view * glm::dvec4(sample.p, 1.0));
    EXPECT_LT(eye.z, -150.0) << "in front, about 200 units away";
    const glm::dvec3 screen = ssrcl::cameraToScreen(read->camera, eye);
    EXPECT_NEAR(screen.x, sample.x + 0.5, 2.0) << sample.x << "," << sample.y;
    EXPECT_NEAR(screen.y, sample.y + 0.5, 2.0) << sample.x << "," << sample.y;
  }
}

// A Houdini (Mantra) file's header, from its oiiotool dump in github.com/ynput/ayon-houdini/issues/76
// (1280x720): worldToCamera looks down -z (worldToNDC's w is minus its camera z) and worldToNDC
// is screen space, y up. Read so, the camera's axis falls on the frame's centre, in front of it,
// and its focal lengths are the dump's own (x 2.414, y = x * 1280/720).
TEST(HoudiniHeaderCamera, MantraDumpReadsAsItsCamera) {
  const Imath::M44f toCamera(-0.243232f, -0.429738f, -0.869577f, 0, -4.55991e-08f, 0.8965f, -0.443043f, 0,  //
                             -0.969968f, 0.107762f, 0.218058f, 0, -0.49336f, -0.356619f, 6.48486f, 1);
  const Imath::M44f toNdc(-0.587216f, -1.84441f, -8.69577e-05f, 0.869577f, -1.10086e-07f, 3.84773f, -4.43043e-05f,
                          0.443043f, -2.34172f, 0.462509f, 2.18058e-05f, -0.218058f, -1.19108f, -1.53059f,
                          0.000648386f, -6.48486f);
  for (int row = 0; row < 4; ++row) EXPECT_NEAR(toNdc[row][3], -toCamera[row][2], 1e-5) << "w = -z, row " << row;
  Imf::Header header(1280, 720);
  header.insert("worldToCamera", Imf::M44fAttribute(toCamera));
  header.insert("worldToNDC", Imf::M44fAttribute(toNdc));
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "mantra.exr");
  ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
  // World points 5 and 50 units down the camera's -z axis (Houdini's viewing direction).
  const Imath::M44f toWorld = toCamera.inverse();
  for (const float d : {5.0f, 50.0f}) {
    Imath::V3f world;
    toWorld.multVecMatrix(Imath::V3f(0.0f, 0.0f, -d), world);
    const glm::dvec3 screen =
        ssrcl::cameraToScreen(read->camera, glm::dvec3(read->camera.view * glm::dvec4(world.x, world.y, world.z, 1.0)));
    EXPECT_NEAR(screen.x, 640.0, 0.05) << d;
    EXPECT_NEAR(screen.y, 360.0, 0.05) << d;
    EXPECT_NEAR(screen.z, d, 1e-3 * d) << "planar depth";
  }
  EXPECT_NEAR(read->camera.projection[0][0], 2.41422, 1e-4);
  EXPECT_NEAR(read->camera.projection[1][1], 2.41422 * 1280.0 / 720.0, 1e-3);
}

// A 3Delight file's header, from its exrheader dump in github.com/johannesvollmer/exrs/issues/90
// (640x480, fieldOfViewHorizontal 45.6036, fieldOfViewVertical 35): worldToCamera the identity and
// a worldToNDC in screen space, y up, whose w is +z. Read so, points down +z fall on the frame's
// centre, and the frame's right and top edges lie at the dump's own fields of view.
TEST(DelightHeaderCamera, DumpReadsAsItsCamera) {
  const Imath::M44f toNdc(2.3787f, 0, 0, 0, 0, 3.17159f, 0, 0, 0, 0, 1, 1, 0, 0, -0.001f, 0);
  Imf::Header header(640, 480);
  header.insert("worldToCamera", Imf::M44fAttribute(Imath::M44f()));
  header.insert("worldToNDC", Imf::M44fAttribute(toNdc));
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(header, "3delight.exr");
  ASSERT_TRUE(read && read->problem.empty()) << (read ? read->problem : "no camera");
  EXPECT_FALSE(read->reversed) << "perspective: the divide tells the camera's axis";
  const auto screen = [&](double x, double y, double z) {
    return ssrcl::cameraToScreen(read->camera, glm::dvec3(read->camera.view * glm::dvec4(x, y, z, 1.0)));
  };
  for (const double d : {2.0, 20.0}) {
    const glm::dvec3 centre = screen(0.0, 0.0, d);
    EXPECT_NEAR(centre.x, 320.0, 1e-3) << d;
    EXPECT_NEAR(centre.y, 240.0, 1e-3) << d;
    EXPECT_NEAR(centre.z, d, 1e-4 * d) << "planar depth";
    EXPECT_NEAR(screen(d * std::tan(45.6036 / 2 * M_PI / 180), 0.0, d).x, 640.0, 0.05) << "right edge";
    EXPECT_NEAR(screen(0.0, d * std::tan(35.0 / 2 * M_PI / 180), d).y, 0.0, 0.05) << "top edge";
  }
}

// `ssrcl trace --append` on an Arnold file keeps its arnold/* attributes beside the pass's camera,
// written as OpenEXR's NDC: it reads back as written.
TEST(ArnoldFileHeaderCamera, CameraWrittenBesideArnoldAttributesReadsBack) {
  ssrcl::Camera camera;
  camera.view = glm::lookAt(glm::dvec3(2.0, -6.0, 3.0), glm::dvec3(0.0, 0.0, 0.5), glm::dvec3(0.0, 0.0, 1.0));
  camera.projection = glm::perspective(0.7, 480.0 / 270.0, 0.1, 100.0);
  camera.width = 480;
  camera.height = 270;
  const glm::dvec3 world(0.7, 0.4, 1.1);
  const glm::dvec3 truth = ssrcl::cameraToScreen(camera, glm::dvec3(camera.view * glm::dvec4(world, 1.0)));
  Imf::Header arnold(480, 270);
  arnold.insert("arnold/version", Imf::StringAttribute("Arnold 4.2.16.2"));
  ssrcl::detail::cameraToHeader(camera, arnold);
  const std::optional<ssrcl::HeaderCamera> read = ssrcl::detail::cameraFromHeader(arnold, "appended.exr");
  ASSERT_TRUE(read && read->problem.empty());
  const glm::dvec3 back = ssrcl::cameraToScreen(read->camera, glm::dvec3(read->camera.view * glm::dvec4(world, 1.0)));
  EXPECT_NEAR(back.x, truth.x, 1e-2);
  EXPECT_NEAR(back.y, truth.y, 1e-2);
  EXPECT_NEAR(back.z, truth.z, 1e-4 * truth.z);
}

}  // namespace
