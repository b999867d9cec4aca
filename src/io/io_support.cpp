#include "io/io_support.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <system_error>

namespace lfcam::io {

namespace fs = std::filesystem;

std::string oneLine(std::string_view text) {
  std::string line;
  line.reserve(text.size());
  for (char ch : text) {
    if (ch == '\n' || ch == '\r') {
      // Libraries report several lines; keep them apart without breaking the one-line rule.
      if (!line.empty() && line.back() != ' ') line += "; ";
    } else {
      line += ch;
    }
  }
  while (!line.empty() && (line.back() == ' ' || line.back() == ';')) line.pop_back();
  return line;
}

Error renamedInMessage(Error error, const fs::path& from, const fs::path& to) {
  const std::string prefix = from.string();
  if (error.message.compare(0, prefix.size(), prefix) == 0) error.message.replace(0, prefix.size(), to.string());
  return error;
}

Status checkSampleCount(const fs::path& path, std::initializer_list<std::uint64_t> dims) {
  std::optional<std::uint64_t> samples = checkedProduct(dims);
  std::string what;
  for (std::uint64_t dim : dims) what += (what.empty() ? "" : " x ") + std::to_string(dim);
  return checkMemory(path.string(), samples ? checkedProduct({*samples, sizeof(float)}) : samples, what + " samples");
}

Status checkClaimFitsFile(const fs::path& path, std::optional<std::uint64_t> bytes, std::uint64_t maxRatio,
                          std::string_view claim) {
  std::error_code ec;
  const std::uint64_t fileSize = fs::file_size(path, ec);
  if (ec || (bytes && *bytes / maxRatio <= fileSize + 1024)) return {};
  return fileError(ErrorCode::Format, path,
                   "truncated or corrupt: the header claims " + std::string(claim) + " but the file has only " +
                       std::to_string(fileSize) + " bytes");
}

Status checkReadableFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) return fileError(ErrorCode::Io, path, "no such file");
  if (fs::is_directory(status)) return fileError(ErrorCode::Usage, path, "is a folder, expected a file");
  if (!fs::is_regular_file(status)) return fileError(ErrorCode::Usage, path, "not a regular file");
  return {};
}

std::string lowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  return extension;
}

std::string shortestNumber(double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

std::vector<std::string> channelNames(int channels) {
  switch (channels) {
    case 1: return {"Y"};
    case 2: return {"Y", "A"};
    case 3: return {"R", "G", "B"};
    case 4: return {"R", "G", "B", "A"};
  }
  std::vector<std::string> names;
  for (int c = 0; c < channels; ++c) names.push_back("channel" + std::to_string(c));
  return names;
}

}  // namespace lfcam::io
