// The CLI's heap (tools/aligned_heap.cpp, linked into this test as into `ssrcl`): blocks of
// 2 MiB and up start on page boundaries, whatever unaligned form of new asked for them; smaller
// ones come from malloc as before; every block holds what is written to it and is given back by
// delete.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

namespace {

constexpr std::size_t kLargeBlock = std::size_t(2) << 20;

bool onPageBoundary(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 4096 == 0; }

TEST(AlignedHeap, LargeBlocksStartOnPageBoundaries) {
#if !SSRCL_ALIGNED_HEAP
  GTEST_SKIP() << "sanitizer build: the CLI keeps the sanitizer's operator new";
#endif
  std::vector<float> image(size_t(1920) * 1080 * 3, 1.0f);  // a 1080p normal pass, 25 MB
  EXPECT_TRUE(onPageBoundary(image.data()));
  auto array = std::make_unique<double[]>(kLargeBlock / sizeof(double));  // exactly the threshold
  EXPECT_TRUE(onPageBoundary(array.get()));
  auto* single = new std::array<char, (size_t(3) << 20) + 1>();  // not a whole number of pages
  EXPECT_TRUE(onPageBoundary(single));
  delete single;
  std::iota(image.begin(), image.end(), 0.0f);
  EXPECT_EQ(image.back(), float(image.size() - 1));
}

TEST(AlignedHeap, SmallBlocksAreMallocs) {
  // Some small blocks may land on a page boundary by chance; a hundred of them all doing so would not.
  std::vector<std::unique_ptr<int[]>> blocks;
  int aligned = 0;
  for (int k = 0; k < 100; ++k) {
    blocks.push_back(std::make_unique<int[]>(64));
    aligned += onPageBoundary(blocks.back().get());
  }
  EXPECT_LT(aligned, 100);
}

}  // namespace
