// Helpers shared by the file readers and writers of src/io: error messages that name the file,
// and the memory budget for one input (memory_budget.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/memory_budget.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam::io {

// "path: what", on one line.
std::string oneLine(std::string_view text);
inline Error fileError(ErrorCode code, const std::filesystem::path& path, std::string_view what) {
  return makeError(code, path.string() + ": " + oneLine(what));
}

// `error` with a leading `from` in its message replaced by `to`: for errors raised while writing a
// hidden temporary that should name the user's destination.
Error renamedInMessage(Error error, const std::filesystem::path& from, const std::filesystem::path& to);

// Ok when width x height x channels (x views) float samples fit in the memory budget
// (memory_budget.hpp), else a Resource error naming the file, the bytes needed and the limit.
Status checkSampleCount(const std::filesystem::path& path, std::initializer_list<std::uint64_t> dims);

// A header claiming `bytes` of samples (unset: more than 64 bits count) that `maxRatio` times the
// file's length could not hold is a truncated or corrupt file: a Format error saying what it
// claims (`claim`, "640x480 pixels"), before anything is allocated for it.
Status checkClaimFitsFile(const std::filesystem::path& path, std::optional<std::uint64_t> bytes, std::uint64_t maxRatio,
                          std::string_view claim);

// Existing regular file, else an Io or Usage error naming it.
Status checkReadableFile(const std::filesystem::path& path);

// The channel names lfcam writes into files that name channels (OpenEXR, TIFF): Y, YA, RGB, RGBA,
// else channel0, channel1, ...
std::vector<std::string> channelNames(int channels);

// Lower case copy of an extension such as ".PNG".
std::string lowerExtension(const std::filesystem::path& path);

// The shortest text that reads back as `value` ("100", "0.25"), for files and messages.
std::string shortestNumber(double value);

}  // namespace lfcam::io
