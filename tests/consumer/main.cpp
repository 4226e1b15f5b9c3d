// A user's program, built against the installed library through its public API only
// (tests/consumer/run.sh): docs/library.md's example (traceFrame: loadFrame with its sidecar camera
// and the input check, trace, the pass written); a trace into the caller's memory with progress
// reports; the version matching the headers; a frame the declared conventions do not explain
// refused; misuse an error.   ssrcl_consumer <G-buffer EXR> <output EXR>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <ssrcl/ssrcl.hpp>

// docs/library.md's example, to the letter (tests/docs/check_library_example.sh): begin
// Traces a Blender frame (its camera beside it or in its header) into a reflection pass EXR.
void traceFrame(const char* input, const char* output) {
  ssrcl::FrameSource source;
  source.file = input;                             // Blender naming and conventions by default
  ssrcl::Frame frame = ssrcl::loadFrame(source);  // passes, camera, input check, conventions

  ssrcl::Device device(ssrcl::DeviceType::Default);  // or GPU, CPU, an index, openDevice("1")
  ssrcl::Pipeline pipeline(device);
  ssrcl::setFrame(pipeline, frame);  // frame must outlive execute()
  pipeline.settings() = ssrcl::qualityPreset("medium");
  pipeline.commit();  // validates, compiles kernels once per device, allocates
  pipeline.execute();
  ssrcl::Image pass = pipeline.output("reflection");
  if (frame.outputForm == ssrcl::OutputForm::GlossyPass)  // a Blender file with base_color, metallic AOVs
    ssrcl::applyGlossyPassForm(pass, frame.gbuffer, frame.camera, std::nullopt);
  ssrcl::writeReflectionExr(output, pass, pipeline.output("distance"), frame.windows);
}
// docs/library.md's example: end

int main(int argc, char** argv) {
  if (argc != 3) {
    std::printf("usage: ssrcl_consumer <G-buffer EXR> <output EXR>\n");
    return 2;
  }
  if (std::strcmp(ssrcl::versionString(), SSRCL_VERSION) != 0 || ssrcl::versionNumber() != SSRCL_VERSION_NUMBER) {
    std::printf("library %s, headers %s\n", ssrcl::versionString(), SSRCL_VERSION);
    return 1;
  }
  try {
    ssrcl::FrameSource source;
    source.file = argv[1];  // Blender naming and conventions by default (source.renderer)
    const ssrcl::Frame frame = ssrcl::loadFrame(source);

    ssrcl::FrameSource wrong = source;  // Blender's normals are world space: the input check refuses this
    wrong.normalSpace = ssrcl::NormalSpace::Camera;
    try {
      ssrcl::loadFrame(wrong);
      std::printf("loadFrame did not refuse normals read in the wrong space\n");
      return 1;
    } catch (const ssrcl::Error& e) {
      if (e.code() != ssrcl::ErrorCode::InvalidInput) throw;
    }

    ssrcl::Device device(ssrcl::DeviceType::CPU);
    ssrcl::Pipeline pipeline(device);
    try {
      pipeline.execute();
      std::printf("execute() before commit() did not throw\n");
      return 1;
    } catch (const ssrcl::Error& e) {
      if (e.code() != ssrcl::ErrorCode::InvalidOperation) throw;
    }
    ssrcl::setFrame(pipeline, frame);
    const int w = frame.camera.width, h = frame.camera.height;
    std::vector<float> reflection(size_t(w) * h * 4, -1.0f);  // the caller's memory
    pipeline.setOutput("reflection", ssrcl::ImageView(reflection.data(), ssrcl::PixelFormat::Float, w, h, 4));
    int reports = 0;
    pipeline.setProgressMonitor([&](double) { return ++reports > 0; });
    pipeline.commit();
    pipeline.execute();
    size_t hits = 0;
    for (size_t i = 0; i < reflection.size(); ++i) {
      if (!std::isfinite(reflection[i]) || reflection[i] < 0.0f) {
        std::printf("output not written or not finite: %g\n", reflection[i]);
        return 1;
      }
      hits += i % 4 == 3 && reflection[i] > 0.0f;
    }
    if (hits == 0 || reports == 0) {
      std::printf("no reflection found (%zu pixels) or no progress reported (%d)\n", hits, reports);
      return 1;
    }

    traceFrame(argv[1], argv[2]);
    std::error_code ec;
    const auto written = std::filesystem::file_size(argv[2], ec);
    if (ec || written == 0) {
      std::printf("traceFrame wrote no %s\n", argv[2]);
      return 1;
    }
  } catch (const ssrcl::Error& e) {
    std::printf("ssrcl error (%s): %s\n", ssrcl::errorCodeName(e.code()), e.what());
    return 1;
  }
  std::printf("ssrcl %s: ok\n", ssrcl::versionString());
  return 0;
}
