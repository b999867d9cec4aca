// Animated GIFs of rendered photographs (focus pulls, orbits of the observer), written through
// OpenImageIO's GIF writer (sRGB-encoded 8-bit, its own palette per frame).
#pragma once

#include <filesystem>
#include <vector>

#include "lfcam/image.hpp"
#include "lfcam/result.hpp"

namespace lfcam {

// Writes `frames` (linear light, all the same size, 1 or 3 channels) as a looping GIF at
// `framesPerSecond`, atomically. Usage error for no frames, mixed sizes or a name not ending in
// .gif.
Status writeAnimatedGif(const std::filesystem::path& path, const std::vector<Image>& frames, int framesPerSecond);

}  // namespace lfcam
