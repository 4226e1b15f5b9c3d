// The glossy-pass output form (issue 13 item 2): E(view, roughness, F0) of Cycles 3.4's Principled
// GGX lobe against a double-precision quadrature of its definition, and `ssrcl trace
// --output-form glossy-pass` as a user runs it: the pass it writes is the incident form times
// that truth per pixel and channel, the form is recorded, bad material channels and resuming a
// batch in the other form are refused; and (issue 24) the form a file gets when none is asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <iostream>
#include <limits>

#include "shading/specular_albedo_tables.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"
#include "support/exr_fixtures.hpp"
#include "support/ggx_reference.hpp"
#include "support/glossy_truth.hpp"
#include "support/run_command.hpp"
#include "support/simple_camera.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

// Cycles' dielectric Fresnel at IOR 1.5 (Specular 0.5), written out here from its definition.
double fresnel15(double c) {
  const double eta = 1.5, g = std::sqrt(eta * eta - 1 + c * c);
  const double a = (g - c) / (g + c), b = (c * (g + c) - 1) / (c * (g - c) + 1);
  return 0.5 * a * a * (1 + b * b);
}

// F of Cycles 3.4's interpolate_fresnel_color: F0 blended to white by the normalised Fresnel.
double principledFresnel(double f0, double cosLH) {
  const double fd0 = fresnel15(1.0), fh = (fresnel15(cosLH) - fd0) / (1 - fd0);
  return f0 * (1 - fh) + fh;
}

// E by the tests' adaptive quadrature in polar coordinates around the mirror direction
// (tests/support/glossy_truth.hpp), of the lobe as Cycles 3.4 defines it: separable Smith.
double albedoTruth(double cosO, double roughness, double f0) {
  const double alpha = roughness * roughness;
  const glm::dvec3 n(0, 0, 1), o(std::sqrt(1 - cosO * cosO), 0, cosO);
  namespace ggx = ssrcl::test::ggx;
  auto lobe = [&](const glm::dvec3& l) {
    if (l.z <= 0) return 0.0;
    const glm::dvec3 h = glm::normalize(o + l);
    return ggx::ndf(h, alpha) * ggx::smithG1(o, alpha) * ggx::smithG1(l, alpha) *
           principledFresnel(f0, glm::dot(o, h)) / (4 * o.z);
  };
  return ssrcl::test::integrateAround(lobe, ggx::mirror(o), alpha, ssrcl::test::hemisphereClip(n), {},
                                      ssrcl::test::Quadrature{});
}

TEST(SpecularAlbedo, MatchesQuadratureOfCyclesLobe) {
  for (double roughness : {0.2, 0.35, 0.5, 0.7, 1.0})
    for (double cosO : {0.15, 0.4, 0.7, 0.95})
      for (double f0 : {0.04, 0.5, 1.0}) {
        const double truth = albedoTruth(cosO, roughness, f0);
        EXPECT_NEAR(ssrcl::integrateSpecularAlbedo(cosO, roughness * roughness)(f0), truth, 1e-3)
            << "r " << roughness << " cos " << cosO << " F0 " << f0;
        // The table between its grid points: bilinear in roughness and angle.
        EXPECT_NEAR(ssrcl::specularAlbedo(roughness, cosO)(f0), truth, 3e-3)
            << "r " << roughness << " cos " << cosO << " F0 " << f0;
      }
}

// The tables the build integrated hold, bit for bit, what the library's integral gives at their
// nodes (a generator built or run otherwise than the library would show here).
TEST(SpecularAlbedo, BuiltTablesAreTheIntegralAtTheirNodes) {
  namespace d = ssrcl::detail;
  for (int r = 0; r <= d::kAlbedoRoughSteps; r += 7)
    for (int c = 0; c <= d::kAlbedoCosSteps; c += 37) {
      double cosO, alpha;
      d::albedoRowArgs(r, c, &cosO, &alpha);
      const ssrcl::SpecularAlbedo e = ssrcl::integrateSpecularAlbedo(cosO, alpha, 64);
      EXPECT_EQ(d::kSpecularAlbedoRows[r][c][0], e.scale) << r << " " << c;
      EXPECT_EQ(d::kSpecularAlbedoRows[r][c][1], e.bias) << r << " " << c;
    }
  for (int r = 0; r <= SSRCL_ALBEDO_STEPS; r += 4)
    for (int c = 0; c <= SSRCL_ALBEDO_STEPS; c += 5) {
      double cosO, alpha;
      d::albedoNodeArgs(r, c, &cosO, &alpha);
      const ssrcl::SpecularAlbedo e = ssrcl::integrateSpecularAlbedo(cosO, alpha, 64);
      EXPECT_EQ(d::kSpecularAlbedoNodes[r][c][0], e.scale) << r << " " << c;
      EXPECT_EQ(d::kSpecularAlbedoNodes[r][c][1], e.bias) << r << " " << c;
    }
}

// A mirror (roughness 0) reflects exactly the Fresnel at the view angle.
TEST(SpecularAlbedo, MirrorIsTheFresnelAtTheViewAngle) {
  for (double cosO : {0.1, 0.5, 1.0})
    for (double f0 : {0.04, 0.3, 1.0})
      EXPECT_NEAR(ssrcl::specularAlbedo(0.0, cosO)(f0), principledFresnel(f0, cosO), 1e-3) << cosO << " " << f0;
}

TEST(SpecularAlbedo, PrincipledF0) {
  const glm::dvec3 base(0.9, 0.5, 0.1);
  EXPECT_EQ(ssrcl::principledF0(base, 0.0), glm::dvec3(0.04));
  EXPECT_EQ(ssrcl::principledF0(base, 1.0), base);
  const glm::dvec3 half = ssrcl::principledF0(base, 0.5);
  EXPECT_NEAR(half.x, 0.47, 1e-12);
  EXPECT_EQ(ssrcl::principledF0({NAN, 2.0, -1.0}, 1.0), glm::dvec3(0.0, 1.0, 0.0));
}

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

// The bundled glossy sample with Blender-named base_color / metallic AOVs added: base colour
// (0.9, 0.6, 0.2) everywhere, metallic 1 on the left half of the frame and 0.25 on the right.
struct MaterialSample {
  ssrcl::test::TempDir dir{"ssrcl-glossy-form"};
  std::string exr = dir.file("shot.exr");
  ssrcl::test::ExrContents original;
  glm::dvec3 base{0.9, 0.6, 0.2};
  // Partly metal on both halves: a pure metal pixel takes its colour (PureMetalPixelsTakeTheirColour).
  double metallic(int x) const { return x < original.width / 2 ? 0.75 : 0.25; }

  MaterialSample() {
    const std::string sample = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/glossy/glossy";
    original = ssrcl::test::readExr(sample + ".exr");
    std::vector<ssrcl::test::ExrChannel> channels;
    for (const auto& [name, channel] : original.channels) channels.push_back(channel);
    const size_t pixels = size_t(original.width) * original.height;
    for (int c = 0; c < 3; ++c)
      channels.push_back({std::string("ViewLayer.base_color.") + "RGB"[c], std::vector<float>(pixels, float(base[c]))});
    std::vector<float> m(pixels);
    for (size_t i = 0; i < pixels; ++i) m[i] = float(metallic(int(i % original.width)));
    channels.push_back({"ViewLayer.metallic.X", m});
    ssrcl::test::writeExr(exr, original.width, original.height, channels);
    std::filesystem::copy_file(sample + ".camera.json", dir.file("shot.camera.json"));
  }
};

TEST(GlossyPassForm, TraceWritesIncidentTimesAlbedoPerPixel) {
  MaterialSample s;
  const std::string incident = s.dir.file("incident.exr"), glossy = s.dir.file("glossy.exr");
  auto r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form incident -o " + shellQuote(incident)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form glossy-pass -o " + shellQuote(glossy)));
  ASSERT_EQ(r.exitCode, 0) << r.output;

  const ssrcl::test::ExrContents a = ssrcl::test::readExr(incident), b = ssrcl::test::readExr(glossy);
  EXPECT_EQ(b.channels.at("A").values, a.channels.at("A").values);  // A is the found fraction in both
  EXPECT_EQ(b.channels.at("distance").values, a.channels.at("distance").values);
  EXPECT_EQ(ssrcl::describeExr(glossy).stringAttributes.at("ssrcl/output_form"), "glossy-pass");
  EXPECT_EQ(ssrcl::describeExr(incident).stringAttributes.at("ssrcl/output_form"), "incident");

  // Truth per pixel: the view angle from the sidecar camera and the floor's normal (Blender: +Z up).
  const ssrcl::Camera camera = ssrcl::loadCameraJson(s.dir.file("shot.camera.json"));
  const glm::dvec3 eye = glm::dvec3(glm::inverse(camera.view)[3]);
  const glm::dmat4 invViewProj = glm::inverse(camera.projection * camera.view);
  const auto& normalZ = s.original.channels.at("ViewLayer.Normal.Z").values;
  const auto& rough = s.original.channels.at("ViewLayer.roughness.X").values;
  int checked = 0;
  for (int y = 7; y < a.height; y += 23)
    for (int x = 5; x < a.width; x += 31) {
      const size_t i = size_t(y) * a.width + x;
      if (a.channels.at("A").values[i] < 0.2f || normalZ[i] < 0.999f || std::abs(x - a.width / 2) < 3) continue;
      const glm::dvec4 q = invViewProj * glm::dvec4(2.0 * (x + 0.5) / a.width - 1.0, 1.0 - 2.0 * (y + 0.5) / a.height, 0, 1);
      const double cosO = glm::normalize(eye - glm::dvec3(q) / q.w).z;
      for (int c = 0; c < 3; ++c) {
        const float in = a.channels.at(std::string(1, "RGB"[c])).values[i];
        if (in < 1e-3f) continue;
        const double f0 = 0.04 * (1 - s.metallic(x)) + s.base[c] * s.metallic(x);
        const double truth = albedoTruth(cosO, rough[i], f0);
        EXPECT_NEAR(b.channels.at(std::string(1, "RGB"[c])).values[i] / in, truth, 5e-3 + 0.01 * truth)
            << "pixel " << x << "," << y << " channel " << c << " roughness " << rough[i] << " cos " << cosO;
        ++checked;
      }
    }
  EXPECT_GT(checked, 60);
}

// Batch releases each frame's G-buffer once traced; the form needs its material passes.
TEST(GlossyPassForm, BatchWritesWhatTraceWrites) {
  MaterialSample s;
  const std::string traced = s.dir.file("traced.exr"), batchOut = s.dir.file("batch") + "/";
  auto r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form glossy-pass -o " + shellQuote(traced)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runCommand(cli("batch " + shellQuote(s.exr) + " --quality draft --output-form glossy-pass -q -o " + shellQuote(batchOut)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const ssrcl::test::ExrContents a = ssrcl::test::readExr(traced),
                                 b = ssrcl::test::readExr(batchOut + std::filesystem::path(s.exr).stem().string() + ".refl.exr");
  for (const char* c : {"R", "G", "B", "A", "distance"}) EXPECT_EQ(b.channels.at(c).values, a.channels.at(c).values) << c;
}

TEST(GlossyPassForm, AnF0PassWorksAndMismatchesAreRefused) {
  MaterialSample s;
  // The base colour channels read as an F0 pass: metallic 1 everywhere.
  const std::string f0 = s.dir.file("f0.exr");
  auto r = runCommand(cli("trace " + shellQuote(s.exr) +
                          " --quality draft --output-form glossy-pass --f0-channels "
                          "ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B -o " +
                          shellQuote(f0)));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  const std::string out = s.dir.file("out.exr");

  r = runCommand(cli("trace " + shellQuote(s.exr) + " --output-form glossy-pass --f0-channels F0.R,F0.G,F0.B -o " +
                     shellQuote(out)));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("missing channel 'F0.R' for the F0 pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(s.exr), std::string::npos) << r.output;

  r = runCommand(cli("trace " + shellQuote(s.exr) + " --output-form glossy-pass --f0-channels F0.R,F0.G -o " +
                     shellQuote(out)));
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("F0 needs 3 comma-separated channel name(s)"), std::string::npos) << r.output;

  // The original sample has no material AOVs: the default names are missing.
  const std::string plain = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/glossy/glossy.exr";
  r = runCommand(cli("trace " + shellQuote(plain) + " --output-form glossy-pass -o " + shellQuote(out)));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("missing channel 'ViewLayer.base_color.R' for the base colour pass"), std::string::npos)
      << r.output;

  // Resuming a batch refuses a pass written in the other form.
  const std::string batchOut = s.dir.file("batch") + "/";
  r = runCommand(cli("batch " + shellQuote(s.exr) + " --quality draft --max-roughness 0 --output-form incident -q -o " +
                     shellQuote(batchOut)));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  r = runCommand(cli("batch " + shellQuote(s.exr) + " --quality draft --max-roughness 0 --output-form glossy-pass -q -o " +
                     shellQuote(batchOut)));
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("output form incident, but glossy-pass is asked now"), std::string::npos) << r.output;

  // The incident form reads the material passes too (they shade hits on glossy pixels): named,
  // they are what it reads by default from this file, the same pass.
  const std::string named = s.dir.file("named.exr"), unnamed = s.dir.file("unnamed.exr");
  r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form incident --metallic-channel "
                     "ViewLayer.metallic.X -o " + shellQuote(named)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form incident -o " + shellQuote(unnamed)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(ssrcl::test::readExr(named).channels.at("R").values, ssrcl::test::readExr(unnamed).channels.at("R").values);
}

// Issue 24: a Blender file holding the base_color and metallic AOVs gets the glossy-pass form with
// no option, said on stderr and in ssrcl/output_form; --output-form incident overrides it; a file
// without them stays incident, and stderr says what that pass is and which AOVs to add.
TEST(GlossyPassForm, BlenderFilesWithMaterialAovsDefaultToIt) {
  MaterialSample s;
  const std::string byDefault = s.dir.file("default.exr"), asked = s.dir.file("asked.exr");
  auto r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft -o " + shellQuote(byDefault)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("ssrcl: output form glossy-pass (as Cycles' Glossy Direct + Indirect"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(s.exr + " holds ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B and "
                                  "ViewLayer.metallic.X"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(ssrcl::describeExr(byDefault).stringAttributes.at("ssrcl/output_form"), "glossy-pass");
  r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form glossy-pass -o " + shellQuote(asked)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("output form"), std::string::npos) << "asked for, not told: " << r.output;
  const ssrcl::test::ExrContents a = ssrcl::test::readExr(byDefault), b = ssrcl::test::readExr(asked);
  for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(a.channels.at(c).values, b.channels.at(c).values) << c;

  const std::string incident = s.dir.file("incident.exr");
  r = runCommand(cli("trace " + shellQuote(s.exr) + " --quality draft --output-form incident -o " + shellQuote(incident)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("output form"), std::string::npos) << r.output;
  EXPECT_EQ(ssrcl::describeExr(incident).stringAttributes.at("ssrcl/output_form"), "incident");
  EXPECT_NE(ssrcl::test::readExr(incident).channels.at("R").values, a.channels.at("R").values);

  // Batch settles it the same way, once for the sequence; -q keeps it quiet.
  const std::string batchOut = s.dir.file("batch") + "/";
  r = runCommand(cli("batch " + shellQuote(s.exr) + " --quality draft -o " + shellQuote(batchOut)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("ssrcl: output form glossy-pass"), std::string::npos) << r.output;
  const std::string batched = batchOut + "shot.refl.exr";
  EXPECT_EQ(ssrcl::describeExr(batched).stringAttributes.at("ssrcl/output_form"), "glossy-pass");
  EXPECT_EQ(ssrcl::test::readExr(batched).channels.at("R").values, a.channels.at("R").values);
  r = runCommand(cli("batch " + shellQuote(s.exr) + " --quality draft -q --overwrite -o " + shellQuote(batchOut)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("output form"), std::string::npos) << r.output;

  // The bundled sample has no material AOVs: incident, and what to add.
  const std::string plain = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/glossy/glossy.exr";
  const std::string plainOut = s.dir.file("plain.exr");
  r = runCommand(cli("trace " + shellQuote(plain) + " --quality draft -o " + shellQuote(plainOut)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const std::string& said :
       {std::string("ssrcl: output form incident: the radiance reaching the surface over its specular lobe, before the "
                    "Fresnel that Cycles' Glossy Direct + Indirect keep"),
        plain + " has no ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B and ViewLayer.metallic.X",
        std::string("add a base_color (Color) and a metallic (Value) AOV fed from each Principled BSDF (the ssrcl "
                    "Blender add-on's Set Up does)")})
    EXPECT_NE(r.output.find(said), std::string::npos) << said << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
  EXPECT_EQ(ssrcl::describeExr(plainOut).stringAttributes.at("ssrcl/output_form"), "incident");
}

// Other presets keep the incident form with the same AOVs: their specular passes come with an
// albedo to multiply it by (docs/renderers.md, "Output forms per renderer"). The sample renamed as Arnold names
// its passes (layer "": R,G,B, Z, N.X..., roughness, base_color.R..., metallic).
TEST(GlossyPassForm, OtherPresetsKeepTheIncidentForm) {
  MaterialSample s;
  const ssrcl::test::ExrContents blender = ssrcl::test::readExr(s.exr);
  std::vector<ssrcl::test::ExrChannel> channels;
  for (auto [name, channel] : blender.channels) {
    std::string plain = name.substr(std::string("ViewLayer.").size());
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"Combined.", ""}, {"Depth.Z", "Z"},
                                   {"Normal.", "N."}, {"roughness.X", "roughness"}, {"metallic.X", "metallic"}})
      if (plain.compare(0, from.size(), from) == 0) plain = to + plain.substr(from.size());
    channel.name = plain;
    channels.push_back(channel);
  }
  const std::string arnold = s.dir.file("arnold.exr"), out = s.dir.file("out.exr");
  ssrcl::test::writeExr(arnold, blender.width, blender.height, channels);
  std::filesystem::copy_file(s.dir.file("shot.camera.json"), s.dir.file("arnold.camera.json"));
  auto r = runCommand(cli("trace " + shellQuote(arnold) + " --renderer arnold --quality draft -o " + shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("output form"), std::string::npos) << r.output;
  EXPECT_EQ(ssrcl::describeExr(out).stringAttributes.at("ssrcl/output_form"), "incident");
  r = runCommand(cli("trace " + shellQuote(arnold) + " --renderer arnold --quality draft --output-form glossy-pass -o " +
                     shellQuote(out)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(ssrcl::describeExr(out).stringAttributes.at("ssrcl/output_form"), "glossy-pass");
}

// The library's rule, as Python and the CLI call it: which passes decide, named in `why`.
TEST(GlossyPassForm, DefaultFormOfAGBuffer) {
  MaterialSample s;
  ssrcl::GBufferSource source;
  source.file = s.exr;
  EXPECT_EQ(ssrcl::defaultOutputForm(source).form, ssrcl::OutputForm::Incident);  // no material passes named
  EXPECT_EQ(ssrcl::defaultOutputForm(source).why, "no material passes are named");
  source.baseColorChannels = "ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B";
  source.metallicChannel = "ViewLayer.metallic.X";
  EXPECT_EQ(ssrcl::defaultOutputForm(source).form, ssrcl::OutputForm::GlossyPass);
  source.metallicChannel = "metal|ViewLayer.metallic.X";  // alternatives: either
  EXPECT_EQ(ssrcl::defaultOutputForm(source).form, ssrcl::OutputForm::GlossyPass);
  source.metallicChannel = "metal";
  const ssrcl::DefaultOutputForm missing = ssrcl::defaultOutputForm(source);
  EXPECT_EQ(missing.form, ssrcl::OutputForm::Incident);
  EXPECT_EQ(missing.why, s.exr + " has no metal");
  source.f0Channels = "ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B";  // F0 decides alone
  EXPECT_EQ(ssrcl::defaultOutputForm(source).form, ssrcl::OutputForm::GlossyPass);
  source.materialFile = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/glossy/glossy.exr";  // read from there
  EXPECT_EQ(ssrcl::defaultOutputForm(source).form, ssrcl::OutputForm::Incident);
  source.materialFile = s.dir.file("none.exr");
  EXPECT_THROW(ssrcl::defaultOutputForm(source), ssrcl::Error);
}

// Against Cycles: samples/blender/tinted_glossy, a copper floor (metallic 1 on the left half, 0.25
// on the right, Specular 0.5) whose Glossy Direct + Indirect carry the Principled Fresnel. The
// glossy-pass form, F0 from the render's base_color / metallic AOVs, matches them on the right half
// better than the F0 = 1 sample matches its own (high: 39.7) and takes the pure metal left half's
// colour; the incident form times an untinted E, what a Blender user without a specular colour
// pass would composite, is far off.
TEST(GlossyPassForm, MatchesCyclesOnATintedFloor) {
  const std::string exr = std::string(SSRCL_SOURCE_DIR) + "/samples/blender/tinted_glossy/tinted_glossy.exr";
  const ssrcl::test::CyclesReference ref = ssrcl::test::loadCyclesReference(exr);
  const ssrcl::GBuffer g = ssrcl::test::withMaterialAovs(ref.gbuffer, exr);

  const ssrcl::Image incident = ssrcl::test::traceRender(g, ref.camera);
  ssrcl::Image glossy = incident;
  ssrcl::applyGlossyPassForm(glossy, g, ref.camera, std::nullopt);
  for (float bad : {-1.0f, 1.5f, std::nanf("")}) {  // -1 once meant "no constant": now a bad value
    ssrcl::Image untouched = incident;
    try {
      ssrcl::applyGlossyPassForm(untouched, g, ref.camera, bad);
      ADD_FAILURE() << "constant roughness " << bad << " was accepted";
    } catch (const ssrcl::Error& e) {
      EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("roughness"), std::string::npos) << e.what();
    }
  }

  ssrcl::test::CyclesReference asIs = ref;  // the glossy-pass form is compared with Cycles unscaled
  std::fill(asIs.scale.begin(), asIs.scale.end(), 1.0);
  // The right half's pass is the trace times E; the left half, pure metal, is its render's colour.
  std::vector<size_t> partly, metal;
  for (size_t k : ref.groups.front().second)
    (g.metallic.data[size_t(ref.pixels[k])] >= 0.999f ? metal : partly).push_back(k);
  ASSERT_GT(partly.size(), 1000u);
  ASSERT_GT(metal.size(), 1000u);
  const double psnrGlossy = ssrcl::test::referenceError(asIs, glossy, partly).psnr;
  const double psnrUntinted = ssrcl::test::referenceError(ref, incident, partly).psnr;
  const double psnrMetal = ssrcl::test::referenceError(asIs, glossy, metal).psnr;
  std::cout << "glossy-pass form " << psnrGlossy << " dB, incident times untinted E " << psnrUntinted
            << " dB, metal half " << psnrMetal << " dB\n";
  EXPECT_GT(psnrGlossy, 40.0);                // measured 41.2 at medium (35.4 over both halves, before)
  EXPECT_GT(psnrGlossy, psnrUntinted + 4.0);  // measured 31.7
  EXPECT_GT(psnrMetal, 60.0);                 // measured 93.9
}

// The floor y = 0 under ssrcl::test::perspectiveCamera(w, h) (it looks down at it), an upward
// normal to every pixel: each pixel's planar depth and the unit vector from its floor point to the eye.
struct FloorView {
  ssrcl::Image depth, normal;
  std::vector<glm::dvec3> toEye;
};
FloorView floorView(const ssrcl::Camera& camera, int w, int h) {
  const glm::dmat4 invViewProj = glm::inverse(camera.projection * camera.view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(camera.view)[3]);
  FloorView f{ssrcl::Image(w, h, 1), ssrcl::Image(w, h, 3), std::vector<glm::dvec3>(size_t(w) * h)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const glm::dvec2 ndc(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h);
      const glm::dvec4 a = invViewProj * glm::dvec4(ndc, -1, 1), b = invViewProj * glm::dvec4(ndc, 1, 1);
      const glm::dvec3 pa = glm::dvec3(a) / a.w, pb = glm::dvec3(b) / b.w;
      const glm::dvec3 floorPoint = pa + (pb - pa) * (pa.y / (pa.y - pb.y));
      f.depth.data[i] = float(-(camera.view * glm::dvec4(floorPoint, 1.0)).z);
      f.normal.data[3 * i + 1] = 1.0f;
      f.toEye[i] = glm::normalize(eye - floorPoint);
    }
  return f;
}

// A mixed pixel (Cycles' mean normal of a floor and an object's side, shorter than 1, its depth on
// the floor): its E is the floor's by the floor's share of the mean plus the mean's by the rest, the
// floor being the neighbour on whose plane its point lies; a mixed pixel off every neighbour's
// plane keeps the mean's E. Against the quadrature of the lobe at each normal's view angle.
TEST(GlossyPassForm, MixedPixelTakesItsSurfacesEByShare) {
  const int w = 16, h = 12;
  const ssrcl::Camera camera = ssrcl::test::perspectiveCamera(w, h);  // looks down at the floor y = 0
  const glm::dvec3 up(0, 1, 0), side(0, 0, 1);                        // side: facing the eye
  const double share = 0.7, roughness = 0.2, f0 = 0.04;
  FloorView ground = floorView(camera, w, h);
  const std::vector<glm::dvec3>& toEye = ground.toEye;
  ssrcl::GBuffer g;
  g.depth = ground.depth;
  g.normal = ground.normal;
  g.roughness = ssrcl::Image(w, h, 1);
  std::fill(g.roughness.data.begin(), g.roughness.data.end(), float(roughness));
  g.f0 = ssrcl::Image(w, h, 3);
  std::fill(g.f0.data.begin(), g.f0.data.end(), float(f0));
  const glm::dvec3 mean = share * up + (1 - share) * side;  // length 0.76
  const size_t mixed = 8 * size_t(w) + 8, offPlane = 8 * size_t(w) + 4;
  for (size_t i : {mixed, offPlane})
    for (int c = 0; c < 3; ++c) g.normal.data[3 * i + c] = float(mean[c]);
  g.depth.data[offPlane] *= 0.8f;  // in front of the floor: no neighbour's plane passes through it
  ssrcl::Image pass(w, h, 4);
  std::fill(pass.data.begin(), pass.data.end(), 1.0f);
  ssrcl::applyGlossyPassForm(pass, g, camera, std::nullopt);

  const auto e = [&](const glm::dvec3& n, size_t i) { return albedoTruth(glm::dot(glm::normalize(n), toEye[i]), roughness, f0); };
  const double floorE = e(up, mixed), meanE = e(mean, mixed);
  ASSERT_GT(floorE, meanE * 1.2);  // the case matters: the mean faces the eye more, its Fresnel is lower
  EXPECT_NEAR(pass.data[4 * mixed], share * floorE + (1 - share) * meanE, 5e-3 * floorE);
  const size_t floorPixel = 8 * size_t(w) + 10;
  EXPECT_NEAR(pass.data[4 * floorPixel], e(up, floorPixel), 5e-3 * floorE);
  // Off-plane: toEye from the floor point behind it, the same ray.
  EXPECT_NEAR(pass.data[4 * offPlane], e(mean, offPlane), 5e-3 * floorE);
}

// Pure metal pixels (metallic 1) take their colour, A 1: with no diffuse, sheen or transmission
// lobe, all of their render's light is their glossy reflection. A partly metal pixel (0.99), one
// whose colour is not finite, one whose glossy passes leave light that is not glossy (a metal
// mixed with a diffuse shader, or emissive), and every pixel of an F0 pass (metal or not, it does
// not say) keep the pass times E: against the quadrature of the lobe, as above. The quantity is
// Glossy Direct + Indirect: a tinted Glossy Color (a Glossy BSDF's colour) divides the colour.
TEST(GlossyPassForm, PureMetalPixelsTakeTheirColour) {
  const int w = 4, h = 4;
  const ssrcl::Camera camera = ssrcl::test::perspectiveCamera(w, h);  // looks down at the floor y = 0
  const double roughness = 0.3, base = 0.8;
  const FloorView ground = floorView(camera, w, h);
  ssrcl::GBuffer g;
  g.depth = ground.depth;
  g.normal = ground.normal;
  g.color = ssrcl::Image(w, h, 3);
  for (size_t i = 0; i < g.color.data.size(); ++i) g.color.data[i] = float(2 + i % 3);
  g.roughness = ssrcl::Image(w, h, 1);
  std::fill(g.roughness.data.begin(), g.roughness.data.end(), float(roughness));
  g.baseColor = ssrcl::Image(w, h, 3);
  std::fill(g.baseColor.data.begin(), g.baseColor.data.end(), float(base));
  g.metallic = ssrcl::Image(w, h, 1);
  std::fill(g.metallic.data.begin(), g.metallic.data.end(), 1.0f);
  const auto cosO = [&](size_t i) { return ground.toEye[i].y; };
  const size_t metal = 5, partly = 6, notFinite = 9, mixed = 10, withPasses = 11, tinted = 12;
  g.metallic.data[partly] = 0.99f;
  g.color.data[3 * notFinite + 1] = std::numeric_limits<float>::infinity();
  g.base = ssrcl::Image(w, h, 3);               // the glossy passes' remainder: nil (their rounding) but at `mixed`
  g.base.data[3 * withPasses] = 0.008f * 9.0f;  // 0.8% of the colour's sum (2 + 3 + 4)
  g.base.data[3 * mixed] = 0.5f;
  g.specular = ssrcl::Image(w, h, 3);  // Glossy Color: white (a Principled BSDF) but at `tinted`
  std::fill(g.specular.data.begin(), g.specular.data.end(), 1.0f);
  g.specular.data[3 * tinted] = 0.5f, g.specular.data[3 * tinted + 2] = 0.25f;
  ssrcl::Image pass(w, h, 4);
  std::fill(pass.data.begin(), pass.data.end(), 0.5f);
  ssrcl::Image fromF0 = pass;
  EXPECT_EQ(ssrcl::applyGlossyPassForm(pass, g, camera, std::nullopt), size_t(w * h - 3));  // all but three

  for (int c = 0; c < 3; ++c) EXPECT_EQ(pass.data[4 * metal + c], float(2 + c));
  EXPECT_EQ(pass.data[4 * metal + 3], 1.0f);
  const double f0Partly = 0.99 * base + 0.01 * 0.04;  // Principled: mix(0.08 Specular, base, metallic)
  EXPECT_NEAR(pass.data[4 * partly], 0.5 * albedoTruth(cosO(partly), roughness, f0Partly), 5e-3);
  EXPECT_EQ(pass.data[4 * partly + 3], 0.5f);
  EXPECT_NEAR(pass.data[4 * notFinite + 1], 0.5 * albedoTruth(cosO(notFinite), roughness, base), 5e-3);
  EXPECT_NEAR(pass.data[4 * mixed], 0.5 * albedoTruth(cosO(mixed), roughness, base), 5e-3);
  EXPECT_EQ(pass.data[4 * withPasses + 2], 4.0f);
  EXPECT_EQ(pass.data[4 * tinted], 4.0f);
  EXPECT_EQ(pass.data[4 * tinted + 1], 3.0f);
  EXPECT_EQ(pass.data[4 * tinted + 2], 16.0f);
  for (float v : pass.data) ASSERT_TRUE(std::isfinite(v));

  g.f0 = g.baseColor;  // an F0 pass is read first
  EXPECT_EQ(ssrcl::applyGlossyPassForm(fromF0, g, camera, std::nullopt), 0u);
  EXPECT_NEAR(fromF0.data[4 * metal], 0.5 * albedoTruth(cosO(metal), roughness, base), 5e-3);
  EXPECT_EQ(fromF0.data[4 * metal + 3], 0.5f);
}

}  // namespace
