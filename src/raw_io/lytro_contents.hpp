// What a Lytro container holds, for people: each section's role (refocus-stack JPEG, H.264 stack,
// depth map, raw frame, metadata, ...) from the table of contents, and extraction of it all into
// ordinary files. Used by `lfcam info` and `lfcam extract`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "raw_io/lytro_container.hpp"

namespace lfcam {

enum class LytroItemKind {
  TableOfContents,
  FrameMetadata,
  PrivateMetadata,
  RawFrame,
  Jpeg,
  H264,
  DepthMap,
  ConfidenceMap,
  Component
};
const char* lytroItemKindName(LytroItemKind kind);

struct LytroItem {
  LytroItemKind kind = LytroItemKind::Component;
  const LytroSection* section = nullptr;  // into the container described
  std::string role;                       // where the table of contents names it, in words
  std::string file;                       // the file `extract` writes it to
  int width = 0, height = 0;              // when the table of contents says
  std::optional<double> lambda;           // refocus slices: the focus (lambda) of the slice
};

struct LytroContents {
  std::vector<LytroItem> items;  // one per section, in file order (the LFP header excluded)
  nlohmann::json summary;        // key facts for `info`: camera, frame metadata, counts
};

LytroContents describeLytroContainer(const LytroContainer& container);

// A depth or confidence map's float32 samples, when the table of contents gives its size and the
// section holds exactly that many.
std::optional<Image> floatMap(const LytroItem& item);

// Writes every item into `folder` (atomically): JPEG slices and H.264 streams as they are,
// depth and confidence maps as PFM plus a Turbo-coloured PNG, the table of contents and frame
// metadata as JSON, a raw frame as a 16-bit TIFF of DN, other sections as .bin, and index.json.
Status extractLytroContainer(const LytroContainer& container, const std::filesystem::path& folder,
                             const std::string& where);

}  // namespace lfcam
