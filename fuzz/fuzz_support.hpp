// Helpers for the fuzz targets whose parsers read files or folders, not bytes: the input is
// written to a scratch folder private to this process, the parser runs, the scratch is removed.
#pragma once

#include <unistd.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/memory_budget.hpp"

namespace lfcam::fuzz {

// Every target's LLVMFuzzerInitialize: a memory budget well under -rss_limit_mb (2048), so an
// input asking for more is refused by lfcam's own check, as it would be for a user.
inline int initialize() {
  setMemoryLimit(std::uint64_t(512) << 20);
  return 0;
}

inline std::filesystem::path scratchFolder() {
  static const std::filesystem::path folder = [] {
    auto p = std::filesystem::temp_directory_path() / ("lfcam-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(p);
    return p;
  }();
  return folder;
}

inline void writeBytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// The input as one file named "input<extension>".
template <class F>
void withTempFile(const uint8_t* data, size_t size, const std::string& extension, F&& parse) {
  const auto path = scratchFolder() / ("input" + extension);
  writeBytes(path, std::string_view(reinterpret_cast<const char*>(data), size));
  parse(path);
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

// The input as a folder. Format (scripts/fuzz_seeds.sh writes seeds in it): a sequence of
// "LFCAMFILE <name>\n<content>", each content running to the next "LFCAMFILE " or the end. Names
// keep only [A-Za-z0-9._-]; at most 128 files.
inline constexpr std::string_view kFileMarker = "LFCAMFILE ";

template <class F>
void withTempFolder(const uint8_t* data, size_t size, F&& parse) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto folder = scratchFolder() / "folder";
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  std::filesystem::create_directories(folder);
  size_t at = input.find(kFileMarker);
  for (int files = 0; at != std::string_view::npos && files < 128; ++files) {
    const size_t nameStart = at + kFileMarker.size();
    const size_t nameEnd = input.find('\n', nameStart);
    if (nameEnd == std::string_view::npos) break;
    std::string name;
    for (char c : input.substr(nameStart, nameEnd - nameStart))
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-') name += c;
    const size_t next = input.find(kFileMarker, nameEnd + 1);
    const auto content = input.substr(nameEnd + 1, next == std::string_view::npos ? next : next - nameEnd - 1);
    if (!name.empty() && name != "." && name != ".." && name.size() < 100) writeBytes(folder / name, content);
    at = next;
  }
  parse(folder);
  std::filesystem::remove_all(folder, ec);
}

}  // namespace lfcam::fuzz
