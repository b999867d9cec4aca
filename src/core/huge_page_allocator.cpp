#include "lfcam/huge_page_allocator.hpp"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace lfcam::huge_pages {

namespace {

constexpr std::size_t hugePage = std::size_t(2) << 20;
// Below this the rounding to whole huge pages would waste too large a share.
constexpr std::size_t threshold = 2 * hugePage;

std::size_t roundedUp(std::size_t bytes) { return (bytes + hugePage - 1) / hugePage * hugePage; }

}  // namespace

void* allocate(std::size_t bytes) {
  if (bytes < threshold) return ::operator new(bytes);
  if (bytes > std::size_t(-1) - hugePage) throw std::bad_alloc();
  void* pointer = std::aligned_alloc(hugePage, roundedUp(bytes));
  if (!pointer) throw std::bad_alloc();
  // Advice only: refused (no THP in this kernel), the pages are ordinary ones.
  ::madvise(pointer, roundedUp(bytes), MADV_HUGEPAGE);
  return pointer;
}

void deallocate(void* pointer, std::size_t bytes) noexcept {
  if (bytes < threshold) return ::operator delete(pointer);
  std::free(pointer);
}

}  // namespace lfcam::huge_pages
