// The CLI's heap (tools/huge_page_heap.cpp, linked into this test as into `ssrcl`): blocks of
// 2 MiB and up start on 2 MiB boundaries, whatever form of new asked for them; smaller ones come
// from malloc as before; every block holds what is written to it and is given back by delete.
#include <gtest/gtest.h>

#include <cstdint>
#include <array>
#include <memory>
#include <numeric>
#include <vector>

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

bool onHugePageBoundary(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kHugePage == 0; }

TEST(HugePageHeap, LargeBlocksStartOnHugePageBoundaries) {
#if !SSRCL_HUGE_PAGE_HEAP
  GTEST_SKIP() << "sanitizer build: the CLI keeps the sanitizer's operator new";
#endif
  std::vector<float> image(size_t(1920) * 1080 * 3, 1.0f);  // a 1080p normal pass, 25 MB
  EXPECT_TRUE(onHugePageBoundary(image.data()));
  auto array = std::make_unique<double[]>(kHugePage / sizeof(double));  // exactly one huge page
  EXPECT_TRUE(onHugePageBoundary(array.get()));
  auto* single = new std::array<char, (size_t(3) << 20) + 1>();  // not a whole number of pages
  EXPECT_TRUE(onHugePageBoundary(single));
  delete single;
  std::iota(image.begin(), image.end(), 0.0f);
  EXPECT_EQ(image.back(), float(image.size() - 1));
}

TEST(HugePageHeap, SmallBlocksAreMallocs) {
  // Some small blocks may land on a 2 MiB boundary by chance; a hundred of them all doing so would not.
  std::vector<std::unique_ptr<int[]>> blocks;
  int aligned = 0;
  for (int k = 0; k < 100; ++k) {
    blocks.push_back(std::make_unique<int[]>(64));
    aligned += onHugePageBoundary(blocks.back().get());
  }
  EXPECT_LT(aligned, 100);
}

}  // namespace
