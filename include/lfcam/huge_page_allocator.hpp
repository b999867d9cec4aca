// HugePageAllocator: the allocator of the large sample buffers (LightField, depth's cost volumes
// edof::CostVolume). Buffers of 4 MiB or more are aligned to 2 MiB and marked for transparent huge
// pages (madvise), because a refocus reads hundreds of short row runs scattered over the whole
// light field: with 4 KiB pages nearly every run begins with a TLB miss, with 2 MiB pages a few
// hundred entries cover it all; and faulting in and zeroing 4 KiB at a time was a third of depth's
// CPU (design.md, speed). Smaller
// buffers come from operator new as usual. Where the kernel refuses huge pages, memory is the
// same as before, only aligned. Large buffers are first touched on every thread.
// A buffer may ask for ordinary pages instead (Pages): on a virtual machine whose host takes
// freed memory back, a fresh huge page can cost more to fault in than it saves (measured here: a
// decode of an Illum-size raw, which writes a new 1 GB light field once, is slower with them; a
// refocus, which reads one many times, faster). LFCAM_HUGE_PAGES=0 in the environment leaves out
// the advice everywhere.
// Every buffer comes zeroed (large ones by that first touch), and construct() without a value
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
// rendered), Ordinary for one written once and passed on (a decode's output), since here a fresh
// huge page costs more to fault in than it saves on a single pass (bench/decode_bench).
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
