#include <filesystem>
#include <exception>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "gbuffer_input.hpp"
#include "output_location.hpp"
#include "output_options.hpp"
#include "settings_options.hpp"
#include "ssrcl/ssrcl.hpp"

namespace ssrcl::cli {
namespace {

struct TraceOptions {
  std::string input, output, camera, device;
  GBufferInputOptions in;
  std::vector<std::string> views, viewCameras;
  std::vector<std::string> neighbours;  // views rendered at other moments (ViewTime::Other)
  SettingsOptions settings;
  OutputOptions out;
  bool stats = false;
};

int runTrace(TraceOptions& o) {
  const FrameSource& passes = o.in.source;
  if (o.input.empty() && (passes.colorFile.empty() || passes.depthFile.empty() || passes.normalFile.empty()))
    throw Error(ErrorCode::InvalidArgument, "trace: give a G-buffer EXR, or each of --color, --depth and --normal");
  const std::string mainFile = o.input.empty() ? passes.colorFile : o.input;
  std::error_code ec;
  if (std::filesystem::equivalent(o.output, mainFile, ec))
    throw Error(ErrorCode::InvalidArgument, o.output + ": refusing to overwrite the input G-buffer");
  if (const std::string problem = outputLocationProblem(o.output, false); !problem.empty()) {
    std::cerr << "ssrcl: " << problem << "\n";
    return kExitOutput;
  }

  // The driver loads its libraries and compiler (some 0.15 s of one core) on this thread while
  // another reads the files: the driver stays on the thread that runs it (LLVM keeps per-thread
  // signal state). A bad file is still reported before a missing device.
  struct Read {
    EnvironmentMap environment;
    Frame frame;
    Views views, neighbours;
  };
  std::future<Read> reading = std::async(std::launch::async, [&o] {
    Read r{o.settings.loadEnvironment(), loadFrame(o.in.sourceFor(o.input, o.camera)), {}, {}};
    std::cerr << settleOutputForm(o.in, r.frame);
    r.views = loadViews(o.in, o.views, o.viewCameras);
    r.neighbours = loadViews(o.in, o.neighbours, {});
    return r;
  });
  std::optional<Device> opened;
  std::exception_ptr noDevice;
  try {
    opened.emplace(openDevice(o.device));
  } catch (...) {
    noDevice = std::current_exception();
  }
  const Read read = reading.get();
  if (noDevice) std::rethrow_exception(noDevice);
  const Frame& frame = read.frame;
  const Camera& camera = frame.camera;
  Device& device = *opened;
  Pipeline pipeline(device);
  setFrame(pipeline, frame);
  setViews(pipeline, read.views);
  addViews(pipeline, read.neighbours, ViewTime::Other);
  pipeline.setEnvironment(read.environment);
  pipeline.settings() = o.in.applyTo(o.settings.resolve());
  pipeline.commit();
  pipeline.execute();

  // The pipeline's pass is written as it is in the incident form: copied (64 MB of fresh memory
  // at 2160p) only where the glossy-pass form changes it.
  const Image* reflection = &pipeline.output("reflection");
  Image formed;
  if (o.in.form.resolved() == OutputForm::GlossyPass) {
    formed = *reflection;
    if (const std::size_t metals = toOutputForm(o.in.form, formed, frame.gbuffer, camera, o.in.roughness))
      std::cerr << "ssrcl: " << metals << " pure metal pixels (metallic 1) take their render's colour, their exact "
                << "glossy pass\n";
    reflection = &formed;
  }

  OutputRecord record{o.settings.quality, pipeline.settings(), device.info().name, o.in.form.form,
                      o.settings.environment, o.views, {}};
  record.views.insert(record.views.end(), o.neighbours.begin(), o.neighbours.end());
  ReflectionExrOptions written = writerOptions(o.out, record, mainFile, frame.passes, frame);
  if (pipeline.viewCount() > 0) written.view = &pipeline.output("view");
  try {
    writeReflectionExr(o.output, *reflection, pipeline.output("distance"), written);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::IoError) throw;  // a file that cannot be appended to is bad input
    std::cerr << "ssrcl: " << e.what() << "\n";
    return kExitOutput;
  }
  if (o.stats) {
    const StageTimes& t = pipeline.stageTimes();
    std::cerr << "device: " << device.info().name << "\n"
              << "pixels traced: " << t.tracedPixels << " of " << size_t(camera.width) * camera.height
              << ", rays: " << t.tracedRays << "\n";
    for (const auto& [stage, ms] : t.ms)
      if (stage != "views" || pipeline.viewCount() > 0)  // no views, no such stage (not one of 0 ms)
        std::cerr << "  " << std::left << std::setw(9) << stage << std::right << std::fixed << std::setprecision(3)
                  << std::setw(10) << ms << " ms\n";
  }
  return kExitOk;
}

}  // namespace

Action addTraceCommand(CLI::App& app) {
  auto o = std::make_shared<TraceOptions>();
  CLI::App* cmd = app.add_subcommand("trace", "Compute the reflection pass of one G-buffer");
  cmd->add_option("input", o->input, "G-buffer EXR (Blender multilayer by default)");
  cmd->add_option("-o,--output", o->output, "Output EXR: R,G,B,A (premultiplied, A = confidence), distance")
      ->required();
  cmd->add_option("--camera", o->camera, "Camera JSON (default: <input stem>.camera.json beside the input, else the EXR header's camera)");
  cmd->add_option("--device", o->device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  addViewOptions(*cmd, o->views, o->viewCameras,
                 "Auxiliary view: a G-buffer EXR of the same scene from another camera (repeatable); rays that "
                 "leave the frame or pass behind a surface continue in the views");
  cmd->add_option("--neighbour", o->neighbours,
                  "A view rendered at another moment: a neighbouring frame of the shot (its sidecar or header "
                  "camera), for static geometry; its hits this frame shows have moved are not taken (repeatable; "
                  "what `ssrcl batch` takes as a frame's neighbours)")
      ->allow_extra_args(false);
  addChannelOptions(*cmd, o->in);
  addPassFileOptions(*cmd, o->in);
  addSettingsOptions(*cmd, o->settings);
  addOutputOptions(*cmd, o->out);
  addOutputFormOptions(*cmd, o->in.form);
  cmd->add_flag("--stats", o->stats, "Print per-stage device times (OpenCL profiling) to stderr");
  return [o] { return runTrace(*o); };
}

}  // namespace ssrcl::cli
