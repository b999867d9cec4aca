// The living pictures' shared page (living_page.hpp).
#include "viewer/living_page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "core/atomic_file.hpp"
#include "viewer/image_encode.hpp"
#include "viewer/viewer_assets.hpp"

namespace lfcam {

namespace {

constexpr std::string_view placeholder = "{{LFCAM_DATA}}", stylePlaceholder = "{{LFCAM_DUAL_RANGE_CSS}}";

}  // namespace

Result<std::string> dataUrl(const Image& image, int quality) {
  LFCAM_ASSIGN_OR_RETURN(auto jpeg, encodeImage(image, {.format = EncodedFormat::Jpeg, .jpegQuality = quality}));
  return "data:image/jpeg;base64," + base64Encode(jpeg);
}

Result<std::string> pageWithData(const nlohmann::json& data) {
  const viewer::Asset* page = viewer::findAsset("living.html");
  if (!page) return makeError(ErrorCode::Format, "export-html: the page template is missing from the build");
  std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string escaped;
  escaped.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      escaped += "\\u003c";
    else
      escaped += c;
  }
  // The two-ended slider's style, shared with lfcam view's page.
  const viewer::Asset* dualRange = viewer::findAsset("viewer.dual-range.css");
  std::string html(page->bytes);
  const auto at = html.find(placeholder), styleAt = html.find(stylePlaceholder);
  if (at == std::string::npos || styleAt >= at || !dualRange)
    return makeError(ErrorCode::Format, "export-html: the page template has no data or style slot");
  // The data first: the style slot lies before it, so its position holds.
  html.replace(at, placeholder.size(), escaped);
  html.replace(styleAt, stylePlaceholder.size(), dualRange->bytes);
  return html;
}

Status writePage(const std::filesystem::path& output, const std::string& html) {
  return writeFileAtomically(output, [&](const std::filesystem::path& temporary) -> Status {
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) return makeError(ErrorCode::Io, output.string() + ": cannot write");
    const bool written = std::fwrite(html.data(), 1, html.size(), file) == html.size();
    if (std::fclose(file) != 0 || !written) return makeError(ErrorCode::Io, output.string() + ": cannot write");
    return {};
  });
}

int openingSlice(int width, int height, int slices, const std::function<int(int x, int y)>& sliceAt) {
  std::vector<int> votes(std::size_t(slices), 0);
  for (int y = height / 4; y < height - height / 4; ++y)
    for (int x = width / 4; x < width - width / 4; ++x) ++votes[std::size_t(sliceAt(x, y))];
  return int(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

std::vector<double> slicePositions(const std::vector<double>& focus, const Image& depth) {
  std::vector<double> positions;
  positions.reserve(depth.pixels().size());
  for (const float value : depth.pixels()) {
    const auto above = std::upper_bound(focus.begin(), focus.end(), double(value));
    double position = 0;
    if (above == focus.end()) {
      position = double(focus.size() - 1);
    } else if (above != focus.begin()) {
      const std::size_t k = std::size_t(above - focus.begin()) - 1;
      position = double(k) + (value - focus[k]) / (*above - focus[k]);
    }
    positions.push_back(std::round(position * 1000) / 1000);
  }
  return positions;
}

}  // namespace lfcam
