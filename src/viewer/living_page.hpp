// What every living picture page shares (living_picture.hpp): its images as data: URLs, its data in
// the page template's slot, the slice it opens on, and where a depth map's values lie among the
// slices' focus settings.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"

namespace lfcam {

// A JPEG data: URL of a linear-light image.
Result<std::string> dataUrl(const Image& image, int quality);

// The page template with `data` in its slot: JSON inside a <script> element, '<' escaped so that
// no "</script>" can close it early.
Result<std::string> pageWithData(const nlohmann::json& data);

Status writePage(const std::filesystem::path& output, const std::string& html);

// The slice the page opens on: the one most pixels of the image's central half (in each direction)
// find sharpest, a vote over the page's own labels: a photograph is framed around its subject. Not
// the middle of the stack, which on the Lytro flower (slopes -2 to 2) lies four slices behind the
// flowers. Ties go to the lower slice.
int openingSlice(int width, int height, int slices, const std::function<int(int x, int y)>& sliceAt);

// Where each pixel of `depth` lies in a stack whose slices are focused at `focus` (increasing, in
// the depth map's units): the fractional index, so that a click blends the two slices around it.
// Rounded to thousandths, as the page needs no more.
std::vector<double> slicePositions(const std::vector<double>& focus, const Image& depth);

}  // namespace lfcam
