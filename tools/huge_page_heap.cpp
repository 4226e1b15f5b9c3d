// The CLI owns its process: its large C++ heap blocks (a frame's images, 8-33 MB each at 1080p)
// start on 2 MiB boundaries and are marked for transparent huge pages. Where each first touch of
// a 4 KiB page is a fault, a 1080p `trace` spent 0.13 of its wall on the host images' faults
// (docs/BENCHMARKS.md "Huge pages"); the library's device buffers do the same for themselves
// (host/pipeline/host_backed_buffer.cpp). Replaces the global operator new and delete, which
// every other form of them calls; not in sanitizer builds, whose own keep their checks.
#include <cstdlib>
#include <new>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace {

constexpr std::size_t kHugePage = std::size_t(2) << 20;

void* allocate(std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugePage) {
    void* memory = nullptr;
    if (posix_memalign(&memory, kHugePage, bytes) != 0) throw std::bad_alloc();
    madvise(memory, bytes, MADV_HUGEPAGE);  // advice: where refused, plain pages serve
    return memory;
  }
#endif
  if (void* memory = std::malloc(bytes == 0 ? 1 : bytes)) return memory;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
