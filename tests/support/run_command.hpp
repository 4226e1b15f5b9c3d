#pragma once
#include <string>

namespace ssrcl::test {

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing its output and exit status.
CommandResult runCommand(const std::string& commandLine);

// Single-quotes an argument for the shell.
std::string shellQuote(const std::string& arg);

}  // namespace ssrcl::test
