#include "lfcam/core/detail/huge_page_allocator.hpp"

#include <sys/mman.h>

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
  if (bytes > std::size_t(-1) - hugePage) throw std::bad_alloc();
  void* pointer = std::aligned_alloc(hugePage, roundedUp(bytes));
  if (!pointer) throw std::bad_alloc();
  // Advice only: refused (no THP in this kernel), the pages are ordinary ones. Ordinary ones are
  // asked for explicitly, for kernels that give huge pages to every aligned region.
  const bool huge = pages == Pages::Huge && hugePagesWanted();
  ::madvise(pointer, roundedUp(bytes), huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
  // First touch on every thread: a page fault zeroes a whole 2 MiB page, and on a virtual
  // machine may also wait for the host to back it; std::vector's fill would fault them all in
  // from one thread (bench/decode_bench: this took a quarter of a second off an Illum decode).
  char* bytesAt = static_cast<char*>(pointer);
  parallelFor(0, roundedUp(bytes) / hugePage, 1, [&](std::size_t begin, std::size_t end) {
    std::memset(bytesAt + begin * hugePage, 0, (end - begin) * hugePage);
  });
  return pointer;
}

void deallocate(void* pointer, std::size_t bytes) noexcept {
  if (bytes < threshold) return ::operator delete(pointer);
  std::free(pointer);
}

}  // namespace lfcam::huge_pages
