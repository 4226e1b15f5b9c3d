// Frame patterns, ranges, shards and batch plans: how `ssrcl batch` turns what a user types into
// the list of frames it processes.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "batch_plan.hpp"
#include "frame_sequence.hpp"
#include "ssrcl/error.hpp"
#include "support/temp_dir.hpp"

namespace {

using ssrcl::Error;
using namespace ssrcl::cli;

void touch(const std::string& path) { std::ofstream(path) << "x"; }

TEST(FramePattern, FindsEachSpelling) {
  struct Case {
    const char* path;
    const char* prefix;
    const char* suffix;
    int digits;
  } cases[] = {{"r/sh010.####.exr", "r/sh010.", ".exr", 4},
               {"sh.%04d.exr", "sh.", ".exr", 4},
               {"sh.%d.exr", "sh.", ".exr", 1},
               {"sh.@@@.exr", "sh.", ".exr", 3},
               {"sh_#.exr", "sh_", ".exr", 1},
               {"####.exr", "", ".exr", 4}};
  for (const Case& c : cases) {
    auto p = findFramePattern(c.path);
    ASSERT_TRUE(p) << c.path;
    EXPECT_EQ(p->prefix, c.prefix) << c.path;
    EXPECT_EQ(p->suffix, c.suffix) << c.path;
    EXPECT_EQ(p->digits, c.digits) << c.path;
  }
  EXPECT_FALSE(findFramePattern("renders/shot.exr"));
  EXPECT_FALSE(findFramePattern("100%.exr"));
  EXPECT_THROW(findFramePattern("a.####.b.####.exr"), Error);
  EXPECT_THROW(findFramePattern("a.%04d.@@.exr"), Error);
}

TEST(FramePattern, FormatsAndMatchesFrameNumbers) {
  const FramePattern p = *findFramePattern("r/sh.####.exr");
  EXPECT_EQ(p.format(7), "r/sh.0007.exr");
  EXPECT_EQ(p.format(1001), "r/sh.1001.exr");
  EXPECT_EQ(p.format(123456), "r/sh.123456.exr");
  EXPECT_EQ(p.match("r/sh.1001.exr"), 1001);
  EXPECT_EQ(p.match("r/sh.0007.exr"), 7);
  EXPECT_EQ(p.match("r/sh.123456.exr"), 123456);
  for (const char* other : {"r/sh.01001.exr", "r/sh.7.exr", "r/sh.abcd.exr", "r/sh.1001.exr.bak", "r/sh..exr",
                            "x/sh.1001.exr", "r/sh.-001.exr"})
    EXPECT_FALSE(p.match(other)) << other;
  const FramePattern unpadded = *findFramePattern("sh.%d.exr");
  EXPECT_EQ(unpadded.match("sh.7.exr"), 7);
  EXPECT_FALSE(unpadded.match("sh.07.exr"));
}

TEST(FrameRange, RangesStepsAndLists) {
  EXPECT_EQ(parseFrameRange("1001-1005"), (std::vector<int>{1001, 1002, 1003, 1004, 1005}));
  EXPECT_EQ(parseFrameRange("1001-1010x3"), (std::vector<int>{1001, 1004, 1007, 1010}));
  EXPECT_EQ(parseFrameRange("1001-1240x2").size(), 120u);
  EXPECT_EQ(parseFrameRange("42"), (std::vector<int>{42}));
  EXPECT_EQ(parseFrameRange("5,1-3,3,0"), (std::vector<int>{0, 1, 2, 3, 5}));
  for (const char* bad :
       {"", "a", "5-1", "1-5x0", "1x2", "1-", "-5", "1-5x", "1,,2", "1-2-3", "1.5", "1-5y2", "0-999999999"})
    EXPECT_THROW(parseFrameRange(bad), Error) << bad;
}

TEST(FrameRange, FramesOnDiskAreTheMatchingFiles) {
  ssrcl::test::TempDir dir("ssrcl-seq");
  for (const char* f : {"sh.1003.exr", "sh.1001.exr", "sh.0999.exr", "sh.1002.exr.tmp", "other.1004.exr", "sh.12.exr"})
    touch(dir.file(f));
  EXPECT_EQ(framesOnDisk(*findFramePattern(dir.file("sh.####.exr"))), (std::vector<int>{999, 1001, 1003}));
  EXPECT_TRUE(framesOnDisk(*findFramePattern(dir.file("none.####.exr"))).empty());
  EXPECT_THROW(framesOnDisk(*findFramePattern(dir.file("f####/beauty.exr"))), Error);
}

TEST(FrameRange, GlobsAreSortedFiles) {
  ssrcl::test::TempDir dir("ssrcl-glob");
  for (const char* f : {"b.exr", "a.exr", "c.txt"}) touch(dir.file(f));
  EXPECT_EQ(globFiles(dir.file("*.exr")), (std::vector<std::string>{dir.file("a.exr"), dir.file("b.exr")}));
  EXPECT_TRUE(globFiles(dir.file("*.png")).empty());
  EXPECT_TRUE(isGlob("r/*.exr"));
  EXPECT_TRUE(isGlob("r/sh.100?.exr"));
  EXPECT_FALSE(isGlob("r/sh.1001.exr"));
}

TEST(Shard, ParsesKOverN) {
  const Shard s = parseShard("3/16");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 16);
  for (const char* bad : {"16/16", "-1/4", "1", "a/b", "0/0", "1/", "/4", "2/1"})
    EXPECT_THROW(parseShard(bad), Error) << bad;
}

TEST(Shard, SharesAreDisjointConsecutiveCoverEverythingAndBalance) {
  for (size_t total : {size_t(3), size_t(100)})
    for (int n = 1; n <= 7; ++n) {
      std::vector<int> owners(total, 0);
      for (int k = 0; k < n; ++k) {
        std::vector<size_t> mine;
        for (size_t i = 0; i < total; ++i)
          if (Shard{k, n}.owns(i, total)) {
            ++owners[i];
            mine.push_back(i);
          }
        EXPECT_LE(mine.size(), (total + n - 1) / n);
        EXPECT_GE(mine.size(), total / n);
        if (!mine.empty()) EXPECT_EQ(mine.back() - mine.front() + 1, mine.size()) << k << "/" << n;  // one run
      }
      EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int o) { return o == 1; })) << n << " shards";
    }
}

class Plan : public ::testing::Test {
 protected:
  ssrcl::test::TempDir dir{"ssrcl-plan"};
  std::string frames = dir.file("sh.####.exr");
  void SetUp() override {
    for (const char* f : {"sh.1001.exr", "sh.1002.exr", "sh.1003.exr"}) touch(dir.file(f));
  }
  std::vector<FrameJob> plan(std::vector<std::string> inputs, std::string output, std::string range = "",
                             std::string camera = "") {
    return planBatch({std::move(inputs), std::move(output), std::move(range), std::move(camera)});
  }
};

TEST_F(Plan, PatternToPattern) {
  auto jobs = plan({frames}, dir.file("out/r.####.exr"), "1001-1005x2");
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[1].name, "1003");
  EXPECT_EQ(jobs[1].frame, 1003);
  EXPECT_EQ(jobs[1].input, dir.file("sh.1003.exr"));
  EXPECT_EQ(jobs[1].camera, dir.file("sh.1003.camera.json"));
  EXPECT_EQ(jobs[2].output, dir.file("out/r.1005.exr"));  // missing inputs are planned: they fail, reported
}

TEST_F(Plan, FramesOnDiskByDefaultIntoADirectory) {
  auto jobs = plan({frames}, dir.file("out") + "/");
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[0].output, dir.file("out/sh.1001.refl.exr"));
}

TEST_F(Plan, GlobWithStemAndOneCamera) {
  auto jobs = plan({dir.file("*.exr")}, dir.file("out/{stem}_refl.exr"), "", dir.file("cam.json"));
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[2].name, "sh.1003");
  EXPECT_FALSE(jobs[2].frame);
  EXPECT_EQ(jobs[2].output, dir.file("out/sh.1003_refl.exr"));
  EXPECT_EQ(jobs[2].camera, dir.file("cam.json"));
}

TEST_F(Plan, CameraPatternPerFrame) {
  auto jobs = plan({frames}, dir.file("o.####.exr"), "", dir.file("cams/c.%04d.json"));
  EXPECT_EQ(jobs[0].camera, dir.file("cams/c.1001.json"));
}

TEST_F(Plan, ExplicitFiles) {
  auto jobs = plan({dir.file("sh.1001.exr"), dir.file("sh.1002.exr")}, dir.file("{stem}.refl.exr"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[1].output, dir.file("sh.1002.refl.exr"));
}

TEST_F(Plan, RefusesWhatCannotWork) {
  EXPECT_THROW(plan({frames}, dir.file("one.exr")), Error);                      // all frames to one file
  EXPECT_THROW(plan({frames}, dir.file("sh.####.exr")), Error);                  // over the inputs
  EXPECT_THROW(plan({dir.file("*.exr")}, dir.file("o.####.exr")), Error);        // no frame numbers
  EXPECT_THROW(plan({dir.file("*.exr")}, dir.file("o/"), "1-3"), Error);         // --frames without a pattern
  EXPECT_THROW(plan({dir.file("*.png")}, dir.file("o/")), Error);                // nothing matches
  EXPECT_THROW(plan({dir.file("x.####.exr")}, dir.file("o/")), Error);           // no frame on disk
  EXPECT_THROW(plan({frames, dir.file("sh.1001.exr")}, dir.file("o/")), Error);  // pattern among files
  EXPECT_THROW(plan({}, dir.file("o/")), Error);
}

}  // namespace
