#include "batch_report.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ssrcl/error.hpp"
#include "ssrcl/version.hpp"

namespace ssrcl::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json frameJson(const FrameJob& job, const FrameOutcome& o) {
  json f = {{"name", job.name},
            {"input", job.input},
            {"camera", job.camera},
            {"output", job.output},
            {"status", statusName(o.status)}};
  if (job.frame) f["frame"] = *job.frame;
  if (o.status == FrameStatus::Failed) {
    f["error"] = o.error;
    f["exit_code"] = o.exitCode;
  }
  if (o.status == FrameStatus::Done || o.status == FrameStatus::Failed) {
    f["seconds"] = {{"read", o.readSeconds}, {"compute", o.computeSeconds}, {"write", o.writeSeconds}};
    f["device_ms"] = o.deviceMs;
  }
  return f;
}

}  // namespace

size_t BatchOutcome::count(FrameStatus status) const {
  size_t n = 0;
  for (const FrameOutcome& f : frames) n += f.status == status;
  return n;
}

double BatchOutcome::framesPerSecond() const {
  return run.wallSeconds > 0 ? count(FrameStatus::Done) / run.wallSeconds : 0.0;
}

double BatchOutcome::deviceBusyFraction() const {
  return run.wallSeconds > 0 ? run.deviceMs * 1e-3 / run.wallSeconds : 0.0;
}

void printSummary(std::ostream& out, const BatchOutcome& b) {
  char rates[128];
  std::snprintf(rates, sizeof rates, "%.1f s, %.2f frames/s, device busy %.0f%%", b.run.wallSeconds,
                b.framesPerSecond(), 100.0 * b.deviceBusyFraction());
  out << "ssrcl batch: " << b.jobs.size() << " frames";
  if (b.shard.count > 1) out << " in shard " << b.shard.index << "/" << b.shard.count;
  out << ": " << b.count(FrameStatus::Done) << " done, " << b.count(FrameStatus::Skipped)
      << " skipped (output exists), " << b.count(FrameStatus::Failed) << " failed";
  if (size_t notRun = b.count(FrameStatus::NotRun)) out << ", " << notRun << " not run";
  out << "; " << rates << "\n";
  for (size_t i = 0; i < b.jobs.size(); ++i)
    if (b.frames[i].status == FrameStatus::Failed)
      out << "  failed " << b.jobs[i].name << ": " << b.frames[i].error << "\n";
  if (b.stopSignal)
    out << "interrupted by " << (b.stopSignal == SIGINT ? "SIGINT" : "SIGTERM")
        << ": the same command again finishes the frames not run\n";
  else if (b.run.halted)
    out << "stopped at the first failure\n";
}

void writeReport(const std::string& path, const BatchOutcome& b) {
  json frames = json::array();
  for (size_t i = 0; i < b.jobs.size(); ++i) frames.push_back(frameJson(b.jobs[i], b.frames[i]));
  const json report = {
      {"ssrcl", SSRCL_VERSION},
      {"device", b.device},
      {"shard", {{"index", b.shard.index}, {"count", b.shard.count}}},
      {"frames_total", b.jobs.size()},
      {"done", b.count(FrameStatus::Done)},
      {"skipped", b.count(FrameStatus::Skipped)},
      {"failed", b.count(FrameStatus::Failed)},
      {"not_run", b.count(FrameStatus::NotRun)},
      {"interrupted", b.stopSignal != 0},
      {"stopped_at_failure", b.run.halted},
      {"wall_seconds", b.run.wallSeconds},
      {"device_seconds", b.run.deviceMs * 1e-3},
      {"frames_per_second", b.framesPerSecond()},
      {"device_busy_fraction", b.deviceBusyFraction()},
      {"frames", frames},
  };
  const fs::path target(path);
  const fs::path temp = target.parent_path() / ("." + target.filename().string() + ".tmp." + std::to_string(getpid()));
  std::error_code ec;
  if (!target.parent_path().empty()) fs::create_directories(target.parent_path(), ec);
  {
    std::ofstream file(temp);
    file << report.dump(2) << "\n";
    file.close();
    if (file) fs::rename(temp, target, ec);
    if (!file || ec) {
      fs::remove(temp, ec);
      throw Error(ErrorCode::IoError, path + ": cannot write the report");
    }
  }
}

}  // namespace ssrcl::cli
