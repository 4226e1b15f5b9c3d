#include "frame_sequence.hpp"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void bad(const std::string& message) { throw Error(ErrorCode::InvalidArgument, message); }

constexpr int kMaxFrames = 1000000;

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// A non-negative decimal number of at most 9 digits (fits an int), or nullopt.
std::optional<int> parseNumber(const std::string& text) {
  if (text.empty() || text.size() > 9 || !std::all_of(text.begin(), text.end(), isDigit)) return std::nullopt;
  return std::stoi(text);
}

// A placeholder starting at `at`: its length and digit count, or {0, 0} when there is none.
std::pair<size_t, int> placeholderAt(const std::string& path, size_t at) {
  const char c = path[at];
  if (c == '#' || c == '@') {
    size_t end = at;
    while (end < path.size() && path[end] == c) ++end;
    return {end - at, int(end - at)};
  }
  if (c == '%') {  // %d or %0Nd
    size_t end = at + 1;
    while (end < path.size() && isDigit(path[end])) ++end;
    if (end < path.size() && path[end] == 'd') {
      const std::string width = path.substr(at + 1, end - at - 1);
      if (width.empty()) return {end + 1 - at, 1};
      if (width[0] == '0' && width.size() > 1 && width.size() < 3) return {end + 1 - at, std::stoi(width)};
    }
  }
  return {0, 0};
}

}  // namespace

std::string FramePattern::format(int frame) const {
  std::string number = std::to_string(frame);
  if (int(number.size()) < digits) number.insert(0, size_t(digits) - number.size(), '0');
  return prefix + number + suffix;
}

std::optional<int> FramePattern::match(const std::string& path) const {
  if (path.size() <= prefix.size() + suffix.size() || path.compare(0, prefix.size(), prefix) != 0 ||
      path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  const std::string number = path.substr(prefix.size(), path.size() - prefix.size() - suffix.size());
  std::optional<int> frame = parseNumber(number);
  // Only the spelling format() writes: "1001" for "####", not "01001".
  if (!frame || format(*frame) != path) return std::nullopt;
  return frame;
}

std::optional<FramePattern> findFramePattern(const std::string& path) {
  std::optional<FramePattern> found;
  for (size_t at = 0; at < path.size();) {
    auto [length, digits] = placeholderAt(path, at);
    if (length == 0) {
      ++at;
      continue;
    }
    if (found) bad(path + ": more than one frame placeholder (####, @, %04d)");
    found = FramePattern{path.substr(0, at), path.substr(at + length), digits};
    at += length;
  }
  return found;
}

std::vector<int> parseFrameRange(const std::string& spec) {
  std::set<int> frames;
  size_t start = 0;
  for (;;) {
    const size_t comma = spec.find(',', start);
    const std::string part = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto fail = [&] {
      bad("--frames: '" + part + "' is not a frame, a range FIRST-LAST or a stepped range FIRST-LASTxSTEP");
    };
    const size_t dash = part.find('-');
    const size_t x = part.find('x');
    std::optional<int> first = parseNumber(part.substr(0, std::min(dash, x)));
    std::optional<int> last = first, step = 1;
    if (dash != std::string::npos)
      last = parseNumber(part.substr(dash + 1, x == std::string::npos ? std::string::npos : x - dash - 1));
    if (x != std::string::npos) {
      if (dash == std::string::npos || x < dash) fail();
      step = parseNumber(part.substr(x + 1));
    }
    if (!first || !last || !step || *step < 1) fail();
    if (*last < *first) bad("--frames: '" + part + "' ends before it starts");
    if ((*last - *first) / *step >= kMaxFrames) bad("--frames: '" + part + "' is over a million frames");
    for (long long f = *first; f <= *last; f += *step) frames.insert(int(f));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return {frames.begin(), frames.end()};
}

std::vector<int> framesOnDisk(const FramePattern& pattern) {
  if (pattern.suffix.find('/') != std::string::npos)
    bad(pattern.prefix + "#" + pattern.suffix + ": the frame number is in a directory name; give --frames");
  const fs::path directory = fs::path(pattern.prefix + "0").parent_path();
  std::vector<int> frames;
  std::error_code ec;
  for (fs::directory_iterator it(directory.empty() ? fs::path(".") : directory, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string path = directory.empty() ? it->path().filename().string() : it->path().string();
    if (std::optional<int> frame = pattern.match(path)) frames.push_back(*frame);
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

bool isGlob(const std::string& path) { return path.find_first_of("*?[") != std::string::npos; }

std::vector<std::string> globFiles(const std::string& pattern) {
  glob_t result{};
  std::vector<std::string> files;
  if (glob(pattern.c_str(), 0, nullptr, &result) == 0)
    for (size_t i = 0; i < result.gl_pathc; ++i)
      if (fs::is_regular_file(result.gl_pathv[i])) files.emplace_back(result.gl_pathv[i]);
  globfree(&result);
  std::sort(files.begin(), files.end());
  return files;
}

Shard parseShard(const std::string& spec) {
  const size_t slash = spec.find('/');
  std::optional<int> index = parseNumber(spec.substr(0, slash));
  std::optional<int> count = slash == std::string::npos ? std::nullopt : parseNumber(spec.substr(slash + 1));
  if (!index || !count || *count < 1 || *index >= *count)
    bad("--shard: expected K/N with 0 <= K < N (e.g. 3/16), got '" + spec + "'");
  return {*index, *count};
}

}  // namespace ssrcl::cli
