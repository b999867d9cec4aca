// HugePageAllocator: the allocator of the large sample buffers (LightField, depth's cost volumes
// edof::CostVolume). Buffers of 4 MiB or more are mappings of their own, aligned to 2 MiB and
// faulted in up front on every thread, a call per part rather than a fault per page (on a virtual
// machine each fault is a trip to the host: `lfcam depth` on antinous 287 k faults and 2.7 s of
// system time before, 57 k and 0.9 s after). Smaller buffers come from operator new as usual.
// Transparent huge pages are opt-in: with LFCAM_HUGE_PAGES=1 in the environment, the buffers that
// ask for them (Pages::Huge, the light fields) are marked for them (madvise), since a refocus reads
// hundreds of short row runs scattered over the whole light field, and with 4 KiB pages nearly
// every run may begin with a TLB miss. Otherwise, and for buffers that ask for ordinary pages, the
// advice is against them: on the virtual machines measured, whose balloon hands freed memory back
// to the host, fresh huge pages fault in slower than ordinary ones (`lfcam depth` on antinous: the
// same user time, system time 1.42 -> 0.62 s, wall 0.93x with its light fields on ordinary pages),
// and a refocus of antinous ran as fast on either (`refocus_bench`, BM_RefocusPages, ratio 0.998;
// design.md, speed). Where the kernel refuses huge pages, memory is the same, only aligned.
// Every buffer comes zeroed (large ones as fresh mappings), and construct() without a value
// leaves it so: std::vector<T, HugePageAllocator<T>>(n) is then zero without a second pass over
// memory that was just written. That holds for fresh allocations only: a vector that shrinks and
// then grows again within its capacity would get back stale values, so the owners (LightField,
// MemoryFloor) only ever size a vector when they create it.
#pragma once

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace lfcam {

// Which pages a large buffer asks for: Huge for one that is read many times (a light field being
// rendered), given only with LFCAM_HUGE_PAGES=1 (above); Ordinary for one written once and passed
// on (a decode's output) or read in order (a cost volume), for which a huge page costs more to fault
// in than it saves (bench/decode_bench).
enum class Pages { Huge, Ordinary };

namespace huge_pages {
void* allocate(std::size_t bytes, Pages pages);  // throws std::bad_alloc like operator new
void deallocate(void* pointer, std::size_t bytes) noexcept;
}  // namespace huge_pages

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  // A buffer keeps its allocator through copies, moves and swaps; any instance frees any buffer.
  using propagate_on_container_copy_assignment = std::true_type;
  using propagate_on_container_move_assignment = std::true_type;
  using propagate_on_container_swap = std::true_type;
  HugePageAllocator() = default;
  explicit HugePageAllocator(Pages kind) noexcept : pages(kind) {}
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>& other) noexcept : pages(other.pages) {}
  T* allocate(std::size_t count) { return static_cast<T*>(huge_pages::allocate(count * sizeof(T), pages)); }
  void deallocate(T* pointer, std::size_t count) noexcept { huge_pages::deallocate(pointer, count * sizeof(T)); }
  // Default-initialisation: the memory is already zero (see above).
  template <typename U>
  void construct(U* pointer) noexcept {
    ::new (static_cast<void*>(pointer)) U;
  }
  template <typename U, typename... Args>
  void construct(U* pointer, Args&&... args) {
    ::new (static_cast<void*>(pointer)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }

  Pages pages = Pages::Huge;
};

}  // namespace lfcam
