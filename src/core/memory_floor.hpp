// MemoryFloor: what reading some bytes once costs on this machine, the yardstick of the speed
// benchmarks (`lfcam bench`, bench/refocus_bench): those bytes at the bandwidth of a threaded
// memcpy of 256 MiB (bytes read plus bytes written per second), on huge pages like a light
// field's samples. Measured anew on every call, since a machine shared with others (a virtual
// one above all) changes speed from one second to the next: a floor taken once would compare a
// photo with the machine of another moment. Benchmark support, not part of the pipeline.
#pragma once

#include <cstddef>
#include <vector>

#include "lfcam/core/detail/huge_page_allocator.hpp"

namespace lfcam {

class MemoryFloor {
 public:
  explicit MemoryFloor(double bytes);

  // Seconds the bytes take at the bandwidth of one copy made now (on all of parallelFor's threads).
  double measure();
  // The median bandwidth of the copies so far, bytes read plus written per second.
  double medianBandwidth() const;

 private:
  double bytes_;
  std::vector<char, HugePageAllocator<char>> source_, destination_;
  std::vector<double> bandwidths_;
};

// The median of `values` (the mean of the middle two for an even count; 0 when empty).
double medianOf(std::vector<double> values);

}  // namespace lfcam
