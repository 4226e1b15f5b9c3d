#include "batch_plan.hpp"

#include <filesystem>
#include <map>
#include <set>

#include "frame_sequence.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/frame.hpp"

namespace ssrcl::cli {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void bad(const std::string& message) { throw Error(ErrorCode::InvalidArgument, message); }

std::string canonical(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

bool isDirectoryTarget(const std::string& output) {
  std::error_code ec;
  return output.back() == '/' || fs::is_directory(output, ec);
}

// `pathTemplate` for one frame: its frame placeholder gets the frame number, "{stem}" the input's
// file name without extension.
std::string expand(const std::string& pathTemplate, const FrameJob& job, const char* option) {
  std::string path = pathTemplate;
  if (std::optional<FramePattern> pattern = findFramePattern(path)) {
    if (!job.frame)
      bad(std::string(option) + " " + pathTemplate + ": has a frame number placeholder but " + job.input +
          " has no frame number; use {stem}");
    path = pattern->format(*job.frame);
  }
  const std::string stem = fs::path(job.input).stem().string();
  for (size_t at; (at = path.find("{stem}")) != std::string::npos;) path.replace(at, 6, stem);
  return path;
}

// Members named, not placed: planBatch fills in the rest (camera, output, back-face depth).
FrameJob framedJob(const FramePattern& pattern, int frame) {
  FrameJob job;
  job.name = std::to_string(frame);
  job.frame = frame;
  job.input = pattern.format(frame);
  return job;
}

FrameJob fileJob(const std::string& file) {
  FrameJob job;
  job.name = fs::path(file).stem().string();
  job.input = file;
  return job;
}

std::vector<FrameJob> listInputs(const BatchRequest& r) {
  if (r.inputs.empty()) bad("batch: give the frames to process (a pattern like 'sh010.####.exr', a glob or files)");
  std::vector<FrameJob> jobs;
  if (r.inputs.size() == 1) {
    const std::string& input = r.inputs[0];
    if (std::optional<FramePattern> pattern = findFramePattern(input)) {
      const std::vector<int> frames = r.frames.empty() ? framesOnDisk(*pattern) : parseFrameRange(r.frames);
      if (frames.empty()) bad(input + ": no frame of this pattern exists; give --frames");
      for (int f : frames) jobs.push_back(framedJob(*pattern, f));
      return jobs;
    }
    if (isGlob(input)) {
      for (const std::string& file : globFiles(input)) jobs.push_back(fileJob(file));
      if (jobs.empty()) bad(input + ": no file matches");
    }
  }
  if (!r.frames.empty()) bad("--frames needs a frame pattern input such as 'sh010.####.exr'");
  if (jobs.empty())
    for (const std::string& input : r.inputs) {
      if (findFramePattern(input) || isGlob(input))
        bad(input + ": a pattern or glob must be the only input (quote it so the shell leaves it alone)");
      jobs.push_back(fileJob(input));
    }
  return jobs;
}

}  // namespace

std::vector<FrameJob> planBatch(const BatchRequest& r) {
  std::vector<FrameJob> jobs = listInputs(r);
  if (r.output.empty()) bad("batch: give an output (-o) pattern, a {stem} template or a directory");
  const std::string output = isDirectoryTarget(r.output) ? (fs::path(r.output) / "{stem}.refl.exr").string() : r.output;
  std::map<std::string, const FrameJob*> byOutput;
  std::set<std::string> inputs;
  for (const FrameJob& job : jobs) inputs.insert(canonical(job.input));
  for (FrameJob& job : jobs) {
    job.output = expand(output, job, "-o");
    job.camera = r.camera.empty() ? sidecarCameraPath(job.input) : expand(r.camera, job, "--camera");
    if (!r.backDepth.empty()) job.backDepth = expand(r.backDepth, job, "--back-depth-file");
    const std::string key = canonical(job.output);
    if (inputs.count(key)) bad(job.output + ": refusing to overwrite an input G-buffer");
    auto [it, fresh] = byOutput.emplace(key, &job);
    if (!fresh)
      bad("-o " + r.output + ": " + it->second->input + " and " + job.input + " would both write " + job.output +
          "; put a frame placeholder (####) or {stem} in it");
  }
  return jobs;
}

void removeStaleTemporaries(const std::vector<const FrameJob*>& jobs) {
  std::map<fs::path, std::set<std::string>> namesByDirectory;
  for (const FrameJob* job : jobs) {
    const fs::path out(job->output);
    namesByDirectory[out.parent_path().empty() ? fs::path(".") : out.parent_path()].insert(out.filename().string());
  }
  for (const auto& [directory, names] : namesByDirectory) {
    std::error_code ec;
    for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string file = it->path().filename().string();
      const size_t tmp = file.rfind(".tmp.");
      if (file.size() < 2 || file[0] != '.' || tmp == std::string::npos) continue;
      if (names.count(file.substr(1, tmp - 1))) fs::remove(it->path(), ec);
    }
  }
}

}  // namespace ssrcl::cli
