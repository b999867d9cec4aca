#include "lfcam/core/detail/huge_page_allocator.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string_view>

#include "core/parallel.hpp"

namespace lfcam::huge_pages {

namespace {

constexpr std::size_t hugePage = std::size_t(2) << 20;
// Below this the rounding to whole huge pages would waste too large a share.
constexpr std::size_t threshold = 2 * hugePage;

std::size_t roundedUp(std::size_t bytes) { return (bytes + hugePage - 1) / hugePage * hugePage; }

// LFCAM_HUGE_PAGES=1 turns huge pages on for the buffers that ask for them (huge_page_allocator.hpp
// says when that pays).
bool hugePagesWanted() {
  static const bool wanted = [] {
    const char* setting = std::getenv("LFCAM_HUGE_PAGES");
    return setting && std::string_view(setting) == "1";
  }();
  return wanted;
}

}  // namespace

void* allocate(std::size_t bytes, Pages pages) {
  if (bytes < threshold) return std::memset(::operator new(bytes), 0, bytes);
  if (bytes > std::size_t(-1) - 2 * hugePage) throw std::bad_alloc();
  // A mapping of its own, aligned by trimming a huge page of slack: fresh anonymous memory is zero
  // (aligned_alloc may hand back memory the heap kept, whose stale values only a write clears).
  const std::size_t size = roundedUp(bytes);
  void* mapped = ::mmap(nullptr, size + hugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  char* const start = static_cast<char*>(mapped);
  char* const bytesAt = start + (hugePage - reinterpret_cast<std::uintptr_t>(start) % hugePage) % hugePage;
  if (bytesAt > start) ::munmap(start, std::size_t(bytesAt - start));
  if (start + hugePage > bytesAt) ::munmap(bytesAt + size, std::size_t(start + hugePage - bytesAt));
  // Advice only: refused (no THP in this kernel), the pages are ordinary ones. Ordinary ones are
  // asked for explicitly, for kernels that give huge pages to every aligned region.
  const bool huge = pages == Pages::Huge && hugePagesWanted();
  ::madvise(bytesAt, size, huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
  // Faulted in up front, on every thread: one call per part (MADV_POPULATE_WRITE, Linux 5.14)
  // rather than a fault per page, which on a virtual machine is a trip to the host (a 64 MiB cost
  // volume: 0.5 s by first writes from one thread, 0.04 s populated; bench/depth_bench). Where the
  // kernel has no such call, first writes do it, on every thread (from one, zeroing depth's cost
  // volumes took a third of its CPU; decode_bench: a quarter of a second off an Illum decode).
  parallelFor(0, size / hugePage, 1, [&](std::size_t begin, std::size_t end) {
    char* part = bytesAt + begin * hugePage;
    const std::size_t length = (end - begin) * hugePage;
    if (::madvise(part, length, MADV_POPULATE_WRITE) != 0) std::memset(part, 0, length);
  });
  return bytesAt;
}

void deallocate(void* pointer, std::size_t bytes) noexcept {
  if (bytes < threshold) return ::operator delete(pointer);
  ::munmap(pointer, roundedUp(bytes));
}

}  // namespace lfcam::huge_pages
