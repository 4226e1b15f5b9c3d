#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "batch_plan.hpp"
#include "batch_report.hpp"
#include "batch_runner.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "frame_sequence.hpp"
#include "gbuffer_input.hpp"
#include "output_location.hpp"
#include "output_options.hpp"
#include "progress_line.hpp"
#include "resume_check.hpp"
#include "settings_options.hpp"
#include "stop_signal.hpp"

namespace ssrcl::cli {
namespace {

struct BatchOptions {
  BatchRequest request;
  std::string device, shard = "0/1", report;
  GBufferInputOptions in;
  std::vector<std::string> views, viewCameras;  // static views, shared by every frame
  int neighbours = 1;                           // K frames each side of frame f as its views
  bool neighboursGiven = false;                 // else the default: see defaultNeighbours
  int neighbourReach = 12;                      // ... the farthest this many frames away
  int temporal = 5;                             // passes of frames f-K..f+K blended into frame f's
  SettingsOptions settings;
  OutputOptions out;
  // Readers and as many writers; a quarter of the cores leaves the rest to a CPU device.
  int ioThreads = int(std::clamp(std::thread::hardware_concurrency() / 4, 1u, 4u));
  bool overwrite = false, failFast = false, quiet = false, dryRun = false;
};

int exitCodeOf(const BatchOutcome& b) {
  if (b.stopSignal) return 128 + b.stopSignal;  // as if the signal had ended it
  for (const FrameOutcome& f : b.frames)
    if (f.status == FrameStatus::Failed) return f.exitCode;
  return kExitOk;
}

// The output form of every frame: settled once, from the first frame on disk of the whole
// sequence (so every shard settles alike); a dry run reads no frame.
void settleBatchOutputForm(BatchOptions& o, const std::vector<FrameJob>& all) {
  if (o.dryRun) return;
  std::error_code ec;
  const auto first = std::find_if(all.begin(), all.end(), [&](const FrameJob& job) {
    return std::filesystem::exists(job.input, ec);
  });
  if (first != all.end()) {
    const std::string formNote = settleOutputForm(o.in, first->input);
    if (!o.quiet) std::cerr << formNote;
  }
  else if (o.in.form.form.empty()) o.in.form.form = outputFormName(OutputForm::Incident);  // each frame fails to read
}

// Without --neighbours: K = 1 where frames are blended (--temporal above 0), as many as the
// sequence and the view limit allow; none with --temporal 0 (each frame alone, as `ssrcl trace`).
int defaultNeighbours(const BatchOptions& o, size_t frames) {
  if (o.neighboursGiven) return o.neighbours;
  if (o.temporal == 0) return 0;
  const long fit = std::min((long(frames) - 1) / 2, (long(Pipeline::kMaxViews) - long(o.views.size())) / 2);
  return int(std::clamp(fit, 0L, long(o.neighbours)));
}

int runBatch(BatchOptions& o) {
  // The blend averages 2K + 1 frames: a rare bright view hit's speckle shrinks by their square
  // root, the cap's loss of light does not (TraceSettings::viewRadianceCap).
  if (o.temporal != 0 && !o.settings.viewRadianceCap)
    o.settings.viewRadianceCap = TraceSettings{}.viewRadianceCap * std::sqrt(2.0f * float(o.temporal) + 1.0f);
  const Shard shard = parseShard(o.shard);
  std::vector<FrameJob> jobs;
  const std::vector<FrameJob> all = planBatch(o.request);
  settleBatchOutputForm(o, all);
  for (size_t i = 0; i < all.size(); ++i)
    if (shard.owns(i, all.size())) jobs.push_back(all[i]);
  std::unique_ptr<NeighbourWindow> neighbours;
  if (const int k = defaultNeighbours(o, all.size()); k != 0)
    neighbours = std::make_unique<NeighbourWindow>(o.in, all, k, o.neighbourReach,
                                                   static_cast<int>(o.views.size()));
  std::unique_ptr<TemporalWindow> temporal;
  if (o.temporal != 0) temporal = std::make_unique<TemporalWindow>(all, o.temporal, o.settings.resolve().seed);
  std::vector<FrameOutcome> outcomes(jobs.size());
  std::vector<const FrameJob*> toRun;
  for (size_t i = 0; i < jobs.size(); ++i) {
    std::error_code ec;
    if (!o.overwrite && std::filesystem::exists(jobs[i].output, ec))
      outcomes[i].status = FrameStatus::Skipped;
    else
      toRun.push_back(&jobs[i]);
  }
  OutputRecord record{o.settings.quality, o.in.applyTo(o.settings.resolve()), "", o.in.form.form,
                      o.settings.environment, o.views, {}};
  for (size_t i = 0; i < jobs.size() && !o.dryRun; ++i)
    if (outcomes[i].status == FrameStatus::Skipped) {
      OutputRecord asked = record;
      if (neighbours)
        for (const std::string& file : neighbours->filesOf(jobs[i].input)) asked.views.push_back(file);
      if (temporal) asked.temporal = temporal->filesOf(jobs[i].input);
      if (const std::string problem = resumeMismatch(jobs[i].output, jobs[i].input, o.out, asked); !problem.empty())
        throw Error(ErrorCode::InvalidArgument, problem);
    }
  if (o.dryRun) {
    for (size_t i = 0; i < jobs.size(); ++i)
      std::cout << jobs[i].name << "\t" << jobs[i].input << "\t" << jobs[i].camera << "\t" << jobs[i].output << "\t"
                << (outcomes[i].status == FrameStatus::Skipped ? "skip" : "run") << "\n";
    return kExitOk;
  }

  // Temporaries an interrupted run left, beside frames still to run and frames finished since
  // (this shard's frames only: another shard's may be being written now).
  std::vector<const FrameJob*> shardJobs;
  for (const FrameJob& job : jobs) shardJobs.push_back(&job);
  removeStaleTemporaries(shardJobs);

  StopSignal stop;
  BatchRun run;
  std::string deviceName;
  if (!toRun.empty()) {
    for (const FrameJob* job : toRun)
      if (const std::string problem = outputLocationProblem(job->output, true); !problem.empty()) {
        std::cerr << "ssrcl: " << problem << "\n";
        return kExitOutput;
      }
    Device device = openDevice(o.device);
    deviceName = device.info().name;
    record.device = deviceName;
    const EnvironmentMap environment = o.settings.loadEnvironment();  // loaded and prefiltered once
    const Views views = loadViews(o.in, o.views, o.viewCameras);       // read and uploaded once
    BatchRunner runner(device, o.in, record, o.out, o.failFast, o.ioThreads);
    runner.setEnvironment(environment);
    runner.setViews(views);
    runner.setNeighbours(std::move(neighbours));
    runner.setTemporal(std::move(temporal));
    ProgressLine progress(toRun.size(), !o.quiet);
    size_t finished = 0, failed = 0;
    run = runner.run(
        jobs, outcomes, [&] { return stop.requested(); },
        [&](size_t i) {
          ++finished;
          if (outcomes[i].status == FrameStatus::Failed) {
            ++failed;
            progress.note("ssrcl: frame " + jobs[i].name + ": " + outcomes[i].error);
          }
          progress.update(finished, failed);
        });
    progress.finish();
  }

  const BatchOutcome batch{jobs, outcomes, run, deviceName, shard, stop.signal()};
  if (!o.quiet) printSummary(std::cerr, batch);
  if (!o.report.empty()) writeReport(o.report, batch);
  return exitCodeOf(batch);
}

}  // namespace

Action addBatchCommand(CLI::App& app) {
  auto o = std::make_shared<BatchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "batch", "Compute the reflection passes of a frame sequence: resumable, one device for all frames");
  cmd->add_option("input", o->request.inputs,
                  "Frames: a pattern ('sh010.####.exr', '%04d', '@@@@'), a quoted glob ('renders/*.exr') or files")
      ->required();
  cmd->add_option("-o,--output", o->request.output,
                  "Outputs: a pattern ('refl/sh010.####.exr'), a template with {stem} ('refl/{stem}.refl.exr'), "
                  "or a directory ('refl/': <stem>.refl.exr in it)")
      ->required();
  cmd->add_option("--frames", o->request.frames,
                  "Frames of a pattern: 1001-1240, 1001-1240x2 (every 2nd), 1001,1005,1010-1020 (default: those on "
                  "disk)");
  cmd->add_option("--camera", o->request.camera,
                  "One camera JSON for all frames, or a pattern/{stem} template (default: <stem>.camera.json beside "
                  "each frame, else the frame's EXR header camera)");
  cmd->add_option("--back-depth-file", o->request.backDepth,
                  "Each frame's back-face depth: a pattern/{stem} template ('back/sh010.####.exr'), as "
                  "`ssrcl trace --back-depth-file` (default: each frame's own BackFaces.Depth.Z, if any)");
  cmd->add_option("--back-depth-channel", o->in.source.backDepthChannel,
                  "Its channel, as `ssrcl trace --back-depth-channel`");
  cmd->add_option("--device", o->device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  addViewOptions(*cmd, o->views, o->viewCameras,
                 "Auxiliary view shared by every frame: a G-buffer EXR of the same (static) scene from another "
                 "camera (repeatable), read and uploaded once; as `ssrcl trace --view`");
  cmd->add_option_function<int>(
         "--neighbours",
         [o](const int& k) {
           o->neighbours = k;
           o->neighboursGiven = true;
         },
         "K: K frames on each side of frame f, spread out to --neighbour-reach (all 2K on one side at the "
         "sequence's ends), are views of frame f, each with its own camera, for static geometry: they show what "
         "lies past its edges; hits frame f shows have moved are not taken. Default: 1 with --temporal (fewer "
         "where the sequence or the view limit allows none), 0 with --temporal 0");
  cmd->add_option("--neighbour-reach", o->neighbourReach,
                  "R: frame f's farthest neighbours are f-R and f+R, the others spread between (R = K: the "
                  "adjacent frames)")
      ->capture_default_str();
  cmd->add_option("--temporal", o->temporal,
                  "K: each frame's pass is blended with those of frames f-K..f+K (each weighing less the farther "
                  "it is, down to 1/(K+1)), each traced with its own seed and read where it shows the same "
                  "reflection (reprojected at the reflected point; refused where depth, normals, hit distance or "
                  "radiance disagree); 0: each frame alone")
      ->capture_default_str()
      ->check(CLI::Range(0, 64));
  cmd->add_option("--shard", o->shard,
                  "K/N: process only share K (0-based) of N, e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT")
      ->capture_default_str();
  cmd->add_option("--io-threads", o->ioThreads, "Threads reading frames, and as many writing them")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--overwrite", o->overwrite, "Recompute frames whose output exists (default: skip them)");
  cmd->add_flag("--fail-fast", o->failFast, "Stop at the first frame that fails (default: report it, go on)");
  cmd->add_option("--report", o->report, "Write a JSON report: totals, frames/s, each frame's status and times");
  cmd->add_flag("-q,--quiet", o->quiet, "No progress line and no summary; failed frames are still reported");
  cmd->add_flag("--dry-run", o->dryRun, "List name, input, camera, output and run/skip for each frame; run nothing");
  addChannelOptions(*cmd, o->in);
  addSettingsOptions(*cmd, o->settings);
  addOutputOptions(*cmd, o->out);
  addOutputFormOptions(*cmd, o->in.form);
  return [o] { return runBatch(*o); };
}

}  // namespace ssrcl::cli
