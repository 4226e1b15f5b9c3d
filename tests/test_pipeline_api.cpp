// The pipeline's public API beyond one commit and execute: caller-owned images of any layout,
// frames of a sequence committed on one pipeline, settings changed after commit, progress and
// cancel, misuse. Truth is the same pipeline run the plain way (one fresh pipeline, owning Images).
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <cmath>
#include <cstring>

#include "pipeline/device_impl.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/analytic_frame.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::Image;
using ssrcl::ImageView;
using ssrcl::PixelFormat;
using ssrcl::TraceSettings;

using Frame = ssrcl::test::AnalyticFrame;
using ssrcl::test::runFrame;
using ssrcl::test::sharedTestDevice;

// Spheres on a glossy floor; `shift` moves the camera so consecutive frames differ.
Frame render(int width, int height, double shift = 0.0) {
  Frame f = ssrcl::test::renderAnalyticFrame("spheres_on_mirror", width, height, shift);
  for (float& r : f.g.roughness.data) r = 0.3f;  // glossy: every stage runs
  return f;
}

TraceSettings glossy() {
  TraceSettings s;
  s.samplesPerPixel = 2;
  s.denoise = true;
  return s;
}

struct Output {
  Image rgba, distance;
};

// The plain way: a fresh pipeline, Image inputs, outputs read with output().
Output reference(const Frame& f, const TraceSettings& s) {
  ssrcl::Pipeline p(sharedTestDevice());
  runFrame(p, f, s);
  const Image& rgba = p.output("reflection");
  size_t found = 0;  // the comparisons mean something only where the pass is not empty
  for (size_t i = 3; i < rgba.data.size(); i += 4) found += rgba.data[i] > 0.5f;
  EXPECT_GT(found, rgba.data.size() / 4 / 10) << "the scene reflects little";
  return {rgba, p.output("distance")};
}

void expectSame(const Output& a, const Output& b) {
  EXPECT_EQ(a.rgba.data, b.rgba.data);
  EXPECT_EQ(a.distance.data, b.distance.data);
}

TEST(PipelineApi, FramesOfOneSizeReuseThePipelineAndGiveFreshPipelinesOutput) {
  ssrcl::Pipeline p(sharedTestDevice());
  p.settings() = glossy();
  size_t bytes = 0;
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    const Frame f = render(96, 64, 0.05 * k);
    p.setGBuffer(f.g);
    p.setCamera(f.camera);
    p.commit();
    if (k > 0) EXPECT_EQ(p.deviceBytes(), bytes);
    bytes = p.deviceBytes();
    p.execute();
    expectSame({p.output("reflection"), p.output("distance")}, reference(f, glossy()));
  }
  // Another size replans.
  const Frame other = render(64, 96);
  p.setGBuffer(other.g);
  p.setCamera(other.camera);
  p.commit();
  p.execute();
  expectSame({p.output("reflection"), p.output("distance")}, reference(other, glossy()));
}

TEST(PipelineApi, SettingsChangedAfterCommitAreValidatedAndApplied) {
  const Frame f = render(96, 64);
  ssrcl::Pipeline p(sharedTestDevice());
  runFrame(p, f, glossy());
  // More rays and another tracer after commit: execute() plans again.
  TraceSettings changed = glossy();
  changed.samplesPerPixel = 6;
  changed.tracer = ssrcl::Tracer::DDA;
  changed.prefilter = false;
  p.settings() = changed;
  p.execute();
  expectSame({p.output("reflection"), p.output("distance")}, reference(f, changed));
  // A new seed alone needs no new plan (a blending batch's frames each have one), but is applied.
  const std::vector<float> before = p.output("reflection").data;
  changed.seed = 7;
  p.settings() = changed;
  p.execute();
  expectSame({p.output("reflection"), p.output("distance")}, reference(f, changed));
  EXPECT_NE(p.output("reflection").data, before);
  p.settings().samplesPerPixel = 0;
  try {
    p.execute();
    FAIL() << "no error";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidArgument);
    EXPECT_NE(std::string(e.what()).find("spp"), std::string::npos) << e.what();
  }
}

TEST(PipelineApi, ViewsOfAnyLayoutReadAndWriteTheCallersMemory) {
  const Frame f = render(80, 48);
  const int w = f.camera.width, h = f.camera.height;
  // Colour as half in RGBA pixels with padded rows, depth as float with a pixel stride of 8 bytes.
  const size_t colorRow = size_t(w) * 4 * sizeof(Imath::half) + 24;
  std::vector<unsigned char> colorBytes(colorRow * h);
  Image colorAsHalf(w, h, 3);  // what the pipeline sees: the half-rounded values
  std::vector<float> depthPadded(size_t(w) * h * 2, -7.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        const Imath::half v(f.g.color.at(x, y, c));
        std::memcpy(&colorBytes[y * colorRow + (x * 4 + c) * 2], &v, 2);
        colorAsHalf.at(x, y, c) = float(v);
      }
      depthPadded[(size_t(y) * w + x) * 2] = f.g.depth.at(x, y, 0);
    }
  // Outputs: reflection as half, distance as float every other float.
  std::vector<Imath::half> reflection(size_t(w) * h * 4);
  std::vector<float> distance(size_t(w) * h * 2, -1.0f);

  ssrcl::Pipeline p(sharedTestDevice());
  p.setImage("color", ImageView(colorBytes.data(), PixelFormat::Half, w, h, 3, 4 * sizeof(Imath::half), colorRow));
  p.setImage("depth", ImageView(depthPadded.data(), PixelFormat::Float, w, h, 1, 2 * sizeof(float)));
  p.setImage("normal", ImageView(f.g.normal.data.data(), w, h, 3));
  p.setImage("roughness", f.g.roughness);
  p.setOutput("reflection", ImageView(reflection.data(), PixelFormat::Half, w, h, 4));
  p.setOutput("distance", ImageView(distance.data(), PixelFormat::Float, w, h, 1, 2 * sizeof(float)));
  p.setCamera(f.camera);
  p.settings() = glossy();
  p.commit();
  p.execute();

  Frame plain = f;
  plain.g.color = colorAsHalf;
  const Output truth = reference(plain, glossy());
  expectSame({p.output("reflection"), p.output("distance")}, truth);
  size_t wrong = 0;
  for (size_t i = 0; i < truth.rgba.data.size(); ++i)
    wrong += float(reflection[i]) != float(Imath::half(truth.rgba.data[i]));
  for (size_t i = 0; i < truth.distance.data.size(); ++i)
    wrong += distance[2 * i] != truth.distance.data[i] || distance[2 * i + 1] != -1.0f;
  EXPECT_EQ(wrong, 0u);
}

TEST(PipelineApi, ProgressReachesOneAndFalseCancels) {
  const Frame f = render(64, 48);
  ssrcl::Pipeline p(sharedTestDevice());
  p.setGBuffer(f.g);
  p.setCamera(f.camera);
  p.settings() = glossy();
  std::vector<double> seen;
  p.setProgressMonitor([&](double done) {
    seen.push_back(done);
    return true;
  });
  p.commit();
  p.execute();
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
  const Image before = p.output("reflection");

  const Frame moved = render(64, 48, 0.2);
  p.setGBuffer(moved.g);
  p.setCamera(moved.camera);
  p.setProgressMonitor([](double) { return false; });
  p.commit();
  try {
    p.execute();
    FAIL() << "not cancelled";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::Cancelled) << e.what();
  }
  EXPECT_EQ(p.output("reflection").data, before.data);  // the cancelled frame wrote nothing
}

TEST(PipelineApi, MisuseIsInvalidOperation) {
  const Frame f = render(32, 32);
  ssrcl::Pipeline p(sharedTestDevice());
  const auto expectInvalidOperation = [&] {
    try {
      p.execute();
      ADD_FAILURE() << "no error";
    } catch (const ssrcl::Error& e) {
      EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidOperation) << e.what();
    }
  };
  expectInvalidOperation();  // never committed
  p.setGBuffer(f.g);
  p.setCamera(f.camera);
  p.commit();
  p.execute();
  p.setCamera(f.camera);  // a camera set since the commit
  expectInvalidOperation();
}

// OIDN's way: images set after commit() with the committed shapes are what the next execute()
// reads, no commit in between; the camera stays the committed one.
TEST(PipelineApi, NewImagesOfTheCommittedShapeNeedNoCommit) {
  const Frame first = render(96, 64), second = render(96, 64, 0.1);
  ssrcl::Pipeline p(sharedTestDevice());
  runFrame(p, first, glossy());
  const Image firstPass = p.output("reflection");

  // The second frame's images seen through the first camera: what a fresh pipeline gives for them.
  const Frame mixed{first.camera, second.g};
  p.setGBuffer(mixed.g);
  p.execute();
  const Output truth = reference(mixed, glossy());
  expectSame({p.output("reflection"), p.output("distance")}, truth);
  EXPECT_NE(truth.rgba.data, firstPass.data) << "the new images change nothing: the test cannot tell";

  // A view of caller memory in another layout, same size and channels, needs none either.
  std::vector<float> padded(first.g.depth.data.size() * 2, -3.0f);
  for (size_t i = 0; i < first.g.depth.data.size(); ++i) padded[2 * i] = first.g.depth.data[i];
  p.setImage("depth", ImageView(padded.data(), PixelFormat::Float, 96, 64, 1, 2 * sizeof(float)));
  p.execute();
  Frame firstDepth = mixed;
  firstDepth.g.depth = first.g.depth;
  expectSame({p.output("reflection"), p.output("distance")}, reference(firstDepth, glossy()));
}

// The constant roughness is one optional setting: set, no roughness image is read and every pixel
// traces as if the image held that value everywhere; out of [0, 1] it is refused by name.
TEST(PipelineApi, ConstantRoughnessReplacesTheRoughnessImage) {
  Frame f = render(96, 64);  // its roughness image is 0.3 everywhere
  const Output truth = reference(f, glossy());
  f.g.roughness = Image();
  TraceSettings constant = glossy();
  constant.constantRoughness = 0.3f;
  ssrcl::Pipeline p(sharedTestDevice());
  runFrame(p, f, constant);
  expectSame({p.output("reflection"), p.output("distance")}, truth);

  for (float wrong : {-0.1f, 1.5f, std::nanf("")}) {
    constant.constantRoughness = wrong;
    try {
      ssrcl::validateSettings(constant);
      ADD_FAILURE() << "no error for " << wrong;
    } catch (const ssrcl::Error& e) {
      EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("parameter roughness must be in [0, 1]"), std::string::npos) << e.what();
    }
  }
  constant.constantRoughness.reset();  // unset: the roughness image is needed again
  p.settings() = constant;
  try {
    p.commit();
    ADD_FAILURE() << "no error";
  } catch (const ssrcl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'roughness' not set"), std::string::npos) << e.what();
  }
}

TEST(PipelineApi, InputsSetRemovedOrResizedSinceCommitNeedCommit) {
  const Frame f = render(48, 32), larger = render(64, 32);
  ssrcl::Pipeline p(sharedTestDevice());
  runFrame(p, f, TraceSettings());
  const auto expectCommitAsked = [&](const std::string& image, const std::string& change) {
    try {
      p.execute();
      ADD_FAILURE() << "no error";
    } catch (const ssrcl::Error& e) {
      EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidOperation) << e.what();
      const std::string message = e.what();
      for (const std::string& part : {"'" + image + "'", change, std::string("commit()")})
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
  };
  p.setImage("depth", larger.g.depth);
  expectCommitAsked("depth", "changed from 48x32 with 1 channel to 64x32 with 1 channel");
  p.setImage("depth", f.g.depth);
  p.execute();  // the committed shape again
  const Image fourChannels(48, 32, 4), none;  // the pipeline follows Images until execute()
  p.setImage("normal", fourChannels);
  expectCommitAsked("normal", "with 4 channels");
  p.setImage("normal", f.g.normal);
  p.setImage("base", f.g.color);
  p.setImage("specular", f.g.color);
  expectCommitAsked("base", "was set");
  p.setImage("base", none);
  p.setImage("specular", none);
  p.setImage("roughness", none);
  expectCommitAsked("roughness", "was removed");
  // After commit() the new shapes are the committed ones (here: no roughness image, a constant).
  p.settings().constantRoughness = 0.3f;
  p.commit();
  p.execute();
}

TEST(PipelineApi, CallersOpenClContextAndQueue) {
  const Frame f = render(80, 48);
  const cl::Device clDevice = ssrcl::detail::DeviceAccess::impl(sharedTestDevice()).device;  // the same device
  const cl::Context context(clDevice);
  const cl::CommandQueue queue(context, clDevice, CL_QUEUE_PROFILING_ENABLE);
  const ssrcl::Device shared(clDevice(), context(), queue());
  EXPECT_EQ(shared.info().name, sharedTestDevice().info().name);
  ssrcl::Pipeline p(shared);
  runFrame(p, f, glossy());
  expectSame({p.output("reflection"), p.output("distance")}, reference(f, glossy()));

  const cl::CommandQueue plain(context, clDevice);  // no profiling: no stage times
  try {
    ssrcl::Device unusable(clDevice(), context(), plain());
    FAIL() << "no error";
  } catch (const ssrcl::Error& e) {
    EXPECT_EQ(e.code(), ssrcl::ErrorCode::InvalidArgument);
    EXPECT_NE(std::string(e.what()).find("CL_QUEUE_PROFILING_ENABLE"), std::string::npos) << e.what();
  }
}

TEST(Version, RuntimeMatchesTheHeaders) {
  EXPECT_STREQ(ssrcl::versionString(), SSRCL_VERSION);
  EXPECT_EQ(ssrcl::versionNumber(), SSRCL_VERSION_MAJOR * 10000 + SSRCL_VERSION_MINOR * 100 + SSRCL_VERSION_PATCH);
}

}  // namespace
