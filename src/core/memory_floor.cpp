#include "core/memory_floor.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/parallel.hpp"

namespace lfcam {

namespace {
constexpr std::size_t copyBytes = std::size_t(256) << 20, slice = std::size_t(4) << 20;
}  // namespace

// Both buffers written first: no page faults timed.
MemoryFloor::MemoryFloor(double bytes) : bytes_(bytes), source_(copyBytes, 1), destination_(copyBytes, 0) {}

double MemoryFloor::measure() {
  const auto start = std::chrono::steady_clock::now();
  parallelFor(0, copyBytes / slice, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
      std::memcpy(destination_.data() + k * slice, source_.data() + k * slice, slice);
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  volatile char sink = destination_[copyBytes / 2];  // the copy is used
  (void)sink;
  const double bandwidth = 2.0 * double(copyBytes) / seconds;
  bandwidths_.push_back(bandwidth);
  return bytes_ / bandwidth;
}

double MemoryFloor::medianBandwidth() const { return medianOf(bandwidths_); }

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace lfcam
