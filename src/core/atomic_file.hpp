// Writing outputs so that a failure (or a kill) never leaves a partial file behind: the content is
// written to a hidden temporary name in the destination's folder, then renamed over the
// destination, which POSIX makes atomic. The temporary name keeps the destination's extension, so
// writers that choose their format by extension still work.
#pragma once

#include <filesystem>
#include <functional>

#include "lfcam/core/result.hpp"

namespace lfcam {

// Runs write(temporaryPath); on success renames it to `destination`, on failure removes it.
Status writeFileAtomically(const std::filesystem::path& destination,
                           const std::function<Status(const std::filesystem::path&)>& write);

// The same for a folder of outputs: write(temporaryFolder) fills a fresh hidden folder beside
// `destination`; then each file in it is renamed into `destination` (created if absent), so every
// file is either old or complete. Files already in `destination` and not rewritten are kept.
Status writeFolderAtomically(const std::filesystem::path& destination,
                             const std::function<Status(const std::filesystem::path&)>& write);

// Removes the temporaries a killed writer left directly in `folder` (a batch redoing a capture
// whose worker died). Only for a folder no other writer is using.
void removeStaleTemporaries(const std::filesystem::path& folder);

}  // namespace lfcam
