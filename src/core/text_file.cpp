#include "core/text_file.hpp"

#include <fstream>
#include <sstream>
#include <system_error>

#include "core/atomic_file.hpp"

namespace lfcam {

Result<std::string> readTextFile(const std::filesystem::path& path, const char* expected, std::uintmax_t maxBytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return makeError(ErrorCode::Usage, path.string() + ": is a folder, expected " + expected);
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorCode::Io, path.string() + ": cannot open");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > maxBytes)
    return makeError(ErrorCode::Format,
                     path.string() + ": " + std::to_string(size) + " bytes, too large for " + expected);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return makeError(ErrorCode::Io, path.string() + ": cannot read");
  return text.str();
}

Status writeTextFileAtomically(const std::filesystem::path& path, const std::string& text) {
  return writeFileAtomically(path, [&](const std::filesystem::path& temporary) -> Status {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write");
    return {};
  });
}

}  // namespace lfcam
