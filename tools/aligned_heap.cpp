// The CLI owns its process: its large C++ heap blocks (a frame's images, 8-33 MB each at 1080p)
// start on page boundaries, so that a CPU device reads and writes them where they lie
// (CL_MEM_USE_HOST_PTR needs the device's buffer alignment, 128 bytes on PoCL, under a page on
// CPU devices; glibc's large blocks sit 16 bytes past a page) instead of copying them into fresh
// memory (host/pipeline/host_backed_buffer.hpp); smaller blocks are cheap to copy. No huge-page
// advice: on a virtual machine that returns freed memory to its host, fresh 2 MiB pages took 3-4x
// the system time of small ones (docs/BENCHMARKS.md "Huge pages"). Replaces the global operator
// new and delete, which every unaligned form of them calls (new with align_val_t goes to
// aligned_alloc: no image asks for it); not in sanitizer builds, whose own keep their checks.
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kLargeBlock = std::size_t(2) << 20;
constexpr std::size_t kPage = 4096;

void* allocate(std::size_t bytes) {
  if (bytes >= kLargeBlock) {
    void* memory = nullptr;
    if (posix_memalign(&memory, kPage, bytes) != 0) throw std::bad_alloc();
    return memory;
  }
  if (void* memory = std::malloc(bytes == 0 ? 1 : bytes)) return memory;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
