// Packed raw samples: unpacking any bytes of the promised length, and packing back, must give
// the same samples (a property, checked: a mismatch traps).
#include <vector>

#include "fuzz_support.hpp"
#include "raw_io/raw_packing.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) { return lfcam::fuzz::initialize(); }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  const auto packing = static_cast<lfcam::RawPacking>(data[0] % 3);
  const std::size_t pixels = std::size_t(data[1]) << 8 | data[2];
  const auto bytes = lfcam::packedByteCount(packing, pixels);
  if (!bytes || *bytes > size - 3) return 0;
  std::vector<std::uint16_t> samples(pixels);
  lfcam::unpackRaw(packing, {data + 3, *bytes}, samples);
  const int bits = lfcam::rawPackingBits(packing);
  for (std::uint16_t s : samples)
    if (s >> bits) __builtin_trap();  // more bits than the packing holds
  const auto packed = lfcam::packRaw(packing, samples);
  std::vector<std::uint16_t> again(pixels);
  lfcam::unpackRaw(packing, packed, again);
  if (again != samples) __builtin_trap();
  return 0;
}
