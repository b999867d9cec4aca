// Helpers shared by the file readers and writers of src/io: error messages that name the file,
// size arithmetic that cannot overflow, and the memory limit for one input.
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "lfcam/result.hpp"

namespace lfcam::io {

// The largest image or light field lfcam reads, in float samples (8 GiB): a header asking for
// more is taken to be corrupt or hostile rather than a reason to try the allocation.
inline constexpr std::uint64_t kMaxSamples = std::uint64_t(1) << 31;

// "path: what", on one line.
std::string oneLine(std::string_view text);
inline Error fileError(ErrorCode code, const std::filesystem::path& path, std::string_view what) {
  return makeError(code, path.string() + ": " + oneLine(what));
}

// `error` with a leading `from` in its message replaced by `to`: for errors raised while writing a
// hidden temporary that should name the user's destination.
Error renamedInMessage(Error error, const std::filesystem::path& from, const std::filesystem::path& to);

// The product of the factors, or nothing when it would not fit in 64 bits.
std::optional<std::uint64_t> checkedProduct(std::initializer_list<std::uint64_t> factors);

// A Resource error when width x height x channels (x views) samples exceed kMaxSamples.
Status checkSampleCount(const std::filesystem::path& path, std::initializer_list<std::uint64_t> dims);

// Existing regular file, else an Io or Usage error naming it.
Status checkReadableFile(const std::filesystem::path& path);

// Lower case copy of an extension such as ".PNG".
std::string lowerExtension(const std::filesystem::path& path);

}  // namespace lfcam::io
