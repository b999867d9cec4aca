#include "core/memory_budget.hpp"

#include <unistd.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lfcam {

std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::uint64_t> factors) {
  std::uint64_t product = 1;
  for (std::uint64_t factor : factors)
    if (__builtin_mul_overflow(product, factor, &product)) return std::nullopt;
  return product;
}

std::optional<std::uint64_t> checkedSum(std::initializer_list<std::uint64_t> terms) {
  std::uint64_t sum = 0;
  for (std::uint64_t term : terms)
    if (__builtin_add_overflow(sum, term, &sum)) return std::nullopt;
  return sum;
}

std::uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return std::uint64_t(8) << 30;  // unknown: assume 8 GiB
  return checkedProduct({std::uint64_t(pages), std::uint64_t(pageSize)}).value_or(UINT64_MAX);
}

namespace {
std::atomic<std::uint64_t> explicitLimit{0};  // 0: not set
}

void setMemoryLimit(std::optional<std::uint64_t> bytes) { explicitLimit = bytes.value_or(0); }

std::uint64_t memoryLimit() {
  if (const std::uint64_t set = explicitLimit.load()) return set;
  if (const char* env = std::getenv("LFCAM_MEMORY_LIMIT"); env && *env) {
    // A bad value in the environment falls back to the default rather than failing every command;
    // the CLI checks it once and reports it.
    if (auto parsed = parseMemorySize(env)) return *parsed;
  }
  return physicalMemoryBytes() / 2;
}

Result<std::uint64_t> parseMemorySize(std::string_view text) {
  const auto bad = [&] {
    return makeError(ErrorCode::Usage, "memory limit '" + std::string(text) +
                                           "': expected bytes with an optional K, M, G or T suffix, or a percentage");
  };
  double number = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (ec != std::errc() || !std::isfinite(number) || number <= 0) return bad();
  std::string_view suffix(end, std::size_t(text.data() + text.size() - end));
  if (suffix.size() == 2 && (suffix[1] == 'B' || suffix[1] == 'b')) suffix.remove_suffix(1);
  double bytes = 0;
  if (suffix == "%") {
    if (number > 100) return bad();
    bytes = double(physicalMemoryBytes()) * number / 100;
  } else {
    int shift = 0;
    if (suffix.empty() || suffix == "B" || suffix == "b")
      shift = 0;
    else if (suffix == "K" || suffix == "k")
      shift = 10;
    else if (suffix == "M" || suffix == "m")
      shift = 20;
    else if (suffix == "G" || suffix == "g")
      shift = 30;
    else if (suffix == "T" || suffix == "t")
      shift = 40;
    else
      return bad();
    bytes = std::ldexp(number, shift);
  }
  if (bytes < 1 || bytes >= 1.8e19) return bad();
  return std::uint64_t(bytes);
}

std::string formatBytes(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 6) value /= 1024, ++unit;
  char text[32];
  if (unit == 0)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(text, sizeof text, "%.1f %s", value, units[unit]);
  return text;
}

Status checkMemory(std::string_view where, std::optional<std::uint64_t> bytes, std::string_view what) {
  const std::uint64_t limit = memoryLimit();
  if (bytes && *bytes <= limit) return {};
  return makeError(ErrorCode::Resource,
                   std::string(where) + ": needs " + (bytes ? formatBytes(*bytes) : std::string("more than 16 EiB")) +
                       " of memory for " + std::string(what) + ", more than the limit of " + formatBytes(limit) +
                       " (raise it with --memory-limit or LFCAM_MEMORY_LIMIT)");
}

}  // namespace lfcam
