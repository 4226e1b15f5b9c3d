#include "output_location.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

namespace ssrcl::cli {

namespace fs = std::filesystem;

std::string outputLocationProblem(const std::string& output, bool createDirectory) {
  const fs::path target(output);
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (createDirectory) fs::create_directories(directory, ec);
  if (!fs::is_directory(directory, ec))
    return output + ": cannot write ('" + directory.string() + "' is not an existing directory" +
           (createDirectory && ec ? ", and creating it failed: " + ec.message() : "") + ")";
  // Named as the writer's temporaries, so a probe left by a killed process is cleaned up with them.
  const fs::path probe =
      directory / ("." + target.filename().string() + ".tmp.probe." + std::to_string(std::random_device{}()));
  std::ofstream stream(probe, std::ios::binary);
  const int error = errno;
  const bool created = bool(stream);
  stream.close();
  fs::remove(probe, ec);
  if (!created)
    return output + ": cannot write (cannot create a file in '" + directory.string() + "': " + std::strerror(error) +
           ")";
  return {};
}

}  // namespace ssrcl::cli
