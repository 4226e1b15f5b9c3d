#pragma once
#include <filesystem>
#include <string>

namespace ssrcl::test {

// A fresh directory under the system temp dir, removed with its content on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& tag = "ssrcl");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace ssrcl::test
