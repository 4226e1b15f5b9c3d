#pragma once
#include <optional>
#include <string>
#include <vector>

namespace ssrcl::cli {

// A frame-number placeholder in a path: "####" or "@@@@" (one digit per character, zero-padded),
// "%04d" or "%d". "sh010.####.exr" is frame 1001 as "sh010.1001.exr".
struct FramePattern {
  std::string prefix, suffix;  // the path around the placeholder
  int digits = 1;              // zero-padded to at least this many

  std::string format(int frame) const;
  // The frame number when `path` is this pattern with one written in, else nullopt.
  std::optional<int> match(const std::string& path) const;
};

// The placeholder of `path`, or nullopt when it has none; Error(InvalidArgument) for two or more.
std::optional<FramePattern> findFramePattern(const std::string& path);

// "1001-1240", "1001-1240x2" (every 2nd), "1001,1003,1010-1020x5": ascending, without repeats.
// Frame numbers are >= 0. Error(InvalidArgument) naming the bad part.
std::vector<int> parseFrameRange(const std::string& spec);

// The frames whose files exist, ascending: what a pattern means when no range is given.
std::vector<int> framesOnDisk(const FramePattern& pattern);

// Files matching a shell glob ("renders/*.exr", '?', "[...]"), sorted; none is not an error.
std::vector<std::string> globFiles(const std::string& glob);
bool isGlob(const std::string& path);

// One farm task's share of a list of `total` items: the consecutive items from total * index /
// count up to total * (index + 1) / count, so N tasks split a list into disjoint parts that
// together cover it, whatever each task's start time or what it finds done. Consecutive, so that
// a task blending frames f-K..f+K (`--temporal`, `--neighbours`) traces 2K frames more than its
// own, not 2K + 1 frames for each.
struct Shard {
  int index = 0;
  int count = 1;
  bool owns(size_t item, size_t total) const {
    return item >= total * size_t(index) / size_t(count) && item < total * size_t(index + 1) / size_t(count);
  }
};
// "K/N" with 0 <= K < N; Error(InvalidArgument) otherwise.
Shard parseShard(const std::string& spec);

}  // namespace ssrcl::cli
