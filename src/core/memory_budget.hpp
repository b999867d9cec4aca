// The memory budget: how much one input may make lfcam allocate, and size arithmetic that cannot
// overflow. Every reader computes what a header asks for with checkedProduct and calls
// checkMemory before allocating, so a corrupt or hostile header is refused with a message instead
// of exhausting the machine.
//
// The limit is, in order: setMemoryLimit (the CLI's --memory-limit), else the environment
// variable LFCAM_MEMORY_LIMIT, else half of the machine's physical memory. Sizes are written as
// bytes with an optional K/M/G/T suffix (powers of 1024) or as a percentage of physical memory:
// "4G", "512M", "75%".
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "lfcam/core/result.hpp"

namespace lfcam {

// The product (sum) of the values, or nothing when it does not fit in 64 bits.
std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::uint64_t> factors);
std::optional<std::uint64_t> checkedSum(std::initializer_list<std::uint64_t> terms);

std::uint64_t physicalMemoryBytes();
std::uint64_t memoryLimit();
void setMemoryLimit(std::optional<std::uint64_t> bytes);  // nothing: back to env/default

// "4G", "512M", "1048576", "50%". A Usage error naming `text` otherwise.
Result<std::uint64_t> parseMemorySize(std::string_view text);
// 1536 -> "1.5 KiB".
std::string formatBytes(std::uint64_t bytes);

// Ok when `bytes` (nothing: overflowed) fits in the budget; else a Resource error
// "<where>: needs <bytes> of memory for <what>, more than the limit of <limit> (...)".
Status checkMemory(std::string_view where, std::optional<std::uint64_t> bytes, std::string_view what);

}  // namespace lfcam
