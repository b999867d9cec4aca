#include "living_picture_output.hpp"

#include <cstdio>

#include "lfcam/atomic_file.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

Status writeLivingPictureFile(const std::filesystem::path& output, const LightField& lightField,
                              const LivingPictureOptions& options) {
  auto make = [&] {
    ProgressBar bar("making " + output.string());
    return makeLivingPicture(lightField, options, [&](double f) { bar(f); });
  };
  LFCAM_ASSIGN_OR_RETURN(const std::string html, make());
  return writeFileAtomically(output, [&](const std::filesystem::path& temporary) -> Status {
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) return makeError(ErrorCode::Io, output.string() + ": cannot write");
    const bool written = std::fwrite(html.data(), 1, html.size(), file) == html.size();
    if (std::fclose(file) != 0 || !written) return makeError(ErrorCode::Io, output.string() + ": cannot write");
    return {};
  });
}

}  // namespace lfcam::cli
