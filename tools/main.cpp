// ssrcl command-line tool: a thin client of the library.
#include <iostream>
#include <thread>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "ssrcl/version.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ssrcl: screen-space reflections for rendered EXR passes (OpenCL)", "ssrcl"};
  app.set_version_flag("--version", std::string("ssrcl ") + SSRCL_VERSION);
  app.require_subcommand(1);
  std::vector<std::pair<CLI::App*, ssrcl::cli::Action>> commands;
  for (auto add : {ssrcl::cli::addDevicesCommand, ssrcl::cli::addTraceCommand, ssrcl::cli::addBatchCommand,
                   ssrcl::cli::addBenchCommand}) {
    size_t before = app.get_subcommands({}).size();
    ssrcl::cli::Action action = add(app);
    commands.emplace_back(app.get_subcommands({})[before], std::move(action));
  }
  // The CLI owns its process: EXR chunks are (de)compressed on every core (a trace reads and
  // writes while the device is idle).
  ssrcl::setExrThreads(int(std::thread::hardware_concurrency()));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);  // prints help/version, or the parse error
    return code == 0 ? 0 : ssrcl::cli::kExitUsage;
  }
  for (auto& [sub, action] : commands) {
    if (!sub->parsed()) continue;
    try {
      return action();
    } catch (const ssrcl::Error& e) {
      std::cerr << "ssrcl: " << e.what() << "\n";
      if (!e.buildLog().empty()) std::cerr << "--- OpenCL build log ---\n" << e.buildLog() << "\n";
      return ssrcl::cli::exitCodeFor(e.code());
    } catch (const std::exception& e) {
      std::cerr << "ssrcl: internal error: " << e.what() << "\n";
      return ssrcl::cli::kExitInternal;
    }
  }
  return ssrcl::cli::kExitUsage;
}
