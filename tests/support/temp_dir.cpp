#include "support/temp_dir.hpp"

#include <random>

namespace ssrcl::test {

TempDir::TempDir(const std::string& tag) {
  std::random_device rd;
  for (;;) {
    auto candidate = std::filesystem::temp_directory_path() / (tag + "-" + std::to_string(rd()));
    if (std::filesystem::create_directory(candidate)) {
      path_ = candidate;
      return;
    }
  }
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace ssrcl::test
