#include "core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace lfcam {

namespace fs = std::filesystem;

namespace {

// A hidden sibling of `destination` that keeps its full name (and so its extension), unique to
// this process and call.
constexpr std::string_view kTemporaryPrefix = ".lfcam-tmp-";

fs::path temporarySibling(const fs::path& destination) {
  static std::atomic<unsigned> counter{0};
  fs::path folder = destination.parent_path();
  std::string name = std::string(kTemporaryPrefix) + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                     "-" + destination.filename().string();
  return folder.empty() ? fs::path(name) : folder / name;
}

Error ioError(const fs::path& path, const std::string& what, const std::error_code& ec) {
  return makeError(ErrorCode::Io, path.string() + ": " + what + ": " + ec.message());
}

// Every writer's own message for a missing folder names the temporary file (HDF5's, libpng's):
// checked first, so that the user reads the name they gave.
Status checkFolderExists(const fs::path& destination) {
  const fs::path folder = destination.parent_path();
  std::error_code ec;
  if (folder.empty() || fs::is_directory(folder, ec)) return {};
  return makeError(ErrorCode::Io,
                   destination.string() + ": cannot write: the folder " + folder.string() + " does not exist");
}

}  // namespace

Status writeFileAtomically(const fs::path& destination, const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  if (fs::is_directory(destination, ec))
    return makeError(ErrorCode::Usage, destination.string() + ": is a folder, expected a file name");
  LFCAM_TRY(checkFolderExists(destination));
  const fs::path temporary = temporarySibling(destination);
  Status written = write(temporary);
  if (!written) {
    fs::remove(temporary, ec);
    return written;
  }
  fs::rename(temporary, destination, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return ioError(destination, "cannot write", ec);
  }
  return {};
}

Status writeFolderAtomically(const fs::path& destination, const std::function<Status(const fs::path&)>& write) {
  std::error_code ec;
  if (fs::exists(destination, ec) && !fs::is_directory(destination, ec))
    return makeError(ErrorCode::Usage, destination.string() + ": exists and is not a folder");
  fs::path base = destination;
  if (base.filename().empty()) base = base.parent_path();  // "out/" -> "out"
  const fs::path temporary = temporarySibling(base);
  fs::create_directories(temporary, ec);
  if (ec) return ioError(temporary, "cannot create folder", ec);
  auto cleanUp = [&] {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
  };
  Status written = write(temporary);
  if (!written) {
    cleanUp();
    return written;
  }
  if (!fs::exists(base, ec)) {
    fs::rename(temporary, base, ec);  // the whole folder appears at once
    if (!ec) return {};
  }
  fs::create_directories(base, ec);
  if (ec) {
    cleanUp();
    return ioError(base, "cannot create folder", ec);
  }
  // Move entries one by one; each rename is atomic. Sub-folders are moved whole.
  for (const auto& entry : fs::directory_iterator(temporary, ec)) {
    const fs::path target = base / entry.path().filename();
    if (entry.is_directory() && fs::exists(target)) fs::remove_all(target, ec);
    fs::rename(entry.path(), target, ec);
    if (ec) {
      cleanUp();
      return ioError(target, "cannot write", ec);
    }
  }
  cleanUp();
  return {};
}

void removeStaleTemporaries(const fs::path& folder) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.path().filename().string().starts_with(kTemporaryPrefix)) stale.push_back(entry.path());
  for (const fs::path& path : stale) fs::remove_all(path, ec);
}

}  // namespace lfcam
