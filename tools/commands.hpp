#pragma once
#include <CLI/CLI.hpp>

namespace ssrcl::cli {

// Each sub-command registers its options on the app and returns the action to run once parsed.
// Actions return the process exit code.
using Action = std::function<int()>;

Action addDevicesCommand(CLI::App& app);
Action addTraceCommand(CLI::App& app);
Action addBatchCommand(CLI::App& app);
Action addBenchCommand(CLI::App& app);

}  // namespace ssrcl::cli
