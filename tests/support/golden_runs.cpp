#include "support/golden_runs.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"

namespace ssrcl::test {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::string fnv1a(const std::vector<float>& values) {
  std::uint64_t h = 1469598103934665603ull;
  for (float v : values) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 0; b < 4; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
  }
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << h;
  return out.str();
}

}  // namespace

void PrintTo(const GoldenRun& run, std::ostream* os) { *os << run.name << ": " << run.input << " " << run.options; }

std::vector<GoldenRun> readGoldenRuns(const std::string& runsFile) {
  std::ifstream in(runsFile);
  if (!in) throw std::runtime_error(runsFile + ": cannot read");
  std::vector<GoldenRun> runs;
  for (std::string line; std::getline(in, line);) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    const size_t a = line.find('|'), b = line.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) throw std::runtime_error(runsFile + ": bad line: " + line);
    runs.push_back({trim(line.substr(0, a)), trim(line.substr(a + 1, b - a - 1)), trim(line.substr(b + 1))});
  }
  return runs;
}

std::string goldenDigest(const std::string& cli, const GoldenRun& run, const std::string& sourceDir,
                         const std::string& workDir) {
  const std::string output = workDir + "/" + run.name + ".exr";
  std::string options = run.options;  // "{source}" stands for the source tree in file options
  for (size_t at; (at = options.find("{source}")) != std::string::npos;) options.replace(at, 8, sourceDir);
  const CommandResult r = runCommand(shellQuote(cli) + " trace " + shellQuote(sourceDir + "/" + run.input) + " -o " +
                                     shellQuote(output) + " --device cpu " + options);
  if (r.exitCode != 0) throw std::runtime_error(run.name + ": ssrcl trace failed:\n" + r.output);
  const ExrContents exr = readExr(output);
  std::string line = run.name;
  for (const char* channel : {"R", "G", "B", "A", "distance"}) {
    auto it = exr.channels.find(channel);
    if (it == exr.channels.end()) throw std::runtime_error(run.name + ": output has no channel " + channel);
    line += std::string(" ") + channel + ":" + fnv1a(it->second.values);
  }
  return line;
}

std::string goldenDeviceLine(const std::string& cli) {
  const CommandResult r = runCommand(shellQuote(cli) + " devices");
  if (r.exitCode != 0) throw std::runtime_error("ssrcl devices failed:\n" + r.output);
  // What rounds the output is the code PoCL generates, named by its target (HSTR: the triple and
  // the CPU kind it compiles for), not the processor's brand name nor the memory free at the time:
  // a recording holds wherever the same target runs (POCL_LLVM_CPU_NAME picks another target).
  // Other platforms are identified by their whole line, less the free memory.
  const auto identity = [](const std::string& line) {
    std::smatch target;
    if (std::regex_search(line, target, std::regex("HSTR: ([^,\\]]+)"))) return "device: PoCL " + target[1].str();
    return "device: " + std::regex_replace(trim(line), std::regex(", [0-9.]+ [KMGT]iB\\]$"), "]");
  };
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (line.find("CPU") != std::string::npos || line.find("cpu") != std::string::npos) return identity(line);
  return identity(r.output.substr(0, r.output.find('\n')));
}

}  // namespace ssrcl::test
