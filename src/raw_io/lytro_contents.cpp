// Describing and extracting Lytro containers (lytro_contents.hpp).
#include "raw_io/lytro_contents.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_metadata.hpp"
#include "raw_io/lytro_raw.hpp"

namespace lfcam {

namespace {

using nlohmann::json;

bool startsWith(const std::vector<std::uint8_t>& bytes, std::initializer_list<std::uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

const json* parentOf(const json& toc, const std::string& pointer, int levels) {
  json::json_pointer p(pointer);
  for (int k = 0; k < levels && !p.empty(); ++k) p = p.parent_pointer();
  return toc.contains(p) ? &toc.at(p) : nullptr;
}

int intOr(const json* j, const char* key, int fallback) {
  if (!j || !j->is_object() || !j->contains(key) || !(*j)[key].is_number_integer()) return fallback;
  return (*j)[key].get<int>();
}

std::string lastWord(const std::string& dotted) {
  const auto dot = dotted.rfind('.');
  return dot == std::string::npos ? dotted : dotted.substr(dot + 1);
}

Status writeBytes(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  out.close();
  if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write");
  return {};
}

Status writeText(const std::filesystem::path& path, const std::string& text) {
  return writeBytes(path, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

// Classifies one reference by the key that names it and the objects around it.
void classify(const json& toc, const LytroReference& ref, LytroItem& item, std::map<std::string, int>& counters) {
  const std::string key = ref.pointer.substr(ref.pointer.rfind('/') + 1);
  const json* parent = parentOf(toc, ref.pointer, 1);
  const std::vector<std::uint8_t>& bytes = item.section->payload;
  auto numbered = [&](const std::string& stem, const std::string& ext) {
    const int n = counters[stem]++;
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "_%02d", n);
    return stem + buffer + ext;
  };
  item.width = intOr(parent, "width", 0);
  item.height = intOr(parent, "height", 0);
  if (key == "metadataRef") {
    item.kind = LytroItemKind::FrameMetadata;
    item.role = "frame metadata";
    item.file = "frame_metadata.json";
  } else if (key == "privateMetadataRef") {
    item.kind = LytroItemKind::PrivateMetadata;
    item.role = "private metadata (serial numbers)";
    item.file = "private_metadata.json";
  } else if (ref.pointer.find("/frame/imageRef") != std::string::npos) {
    item.kind = LytroItemKind::RawFrame;
    item.role = "raw sensor frame";
    item.file = "raw.tiff";
  } else if (ref.pointer.find("depthLut") != std::string::npos || ref.pointer.find("depthMap") != std::string::npos) {
    item.kind = LytroItemKind::DepthMap;
    const json* owner = parentOf(toc, ref.pointer, 2);  // the acceleration holding the map
    if (!item.width) item.width = intOr(owner, "width", 0), item.height = intOr(owner, "height", 0);
    item.role = "depth map (lambda, float32)";
    item.file = counters["depth"]++ ? numbered("depth", "") : "depth";
  } else if (ref.pointer.find("confidenceMap") != std::string::npos) {
    item.kind = LytroItemKind::ConfidenceMap;
    const json* owner = parentOf(toc, ref.pointer, 2);
    if (!item.width) item.width = intOr(owner, "width", 0), item.height = intOr(owner, "height", 0);
    item.role = "depth confidence (float32)";
    item.file = counters["confidence"]++ ? numbered("confidence", "") : "confidence";
  } else if (key == "blockOfImagesRef" || startsWith(bytes, {0, 0, 0, 1})) {
    item.kind = LytroItemKind::H264;
    const json* acceleration = parentOf(toc, ref.pointer, 3);
    std::string type = acceleration && acceleration->contains("type") && (*acceleration)["type"].is_string()
                           ? lastWord((*acceleration)["type"].get<std::string>())
                           : "stack";
    const json* block = parent;
    const int frames = block && block->contains("metadataArray") && (*block)["metadataArray"].is_array()
                           ? int((*block)["metadataArray"].size())
                           : 0;
    item.role = "H.264 stream: " + type + (frames ? ", " + std::to_string(frames) + " frames" : "");
    if (block && block->contains("metadataArray") && (*block)["metadataArray"].is_array() && frames) {
      item.width = intOr(&(*block)["metadataArray"][0], "width", 0);
      item.height = intOr(&(*block)["metadataArray"][0], "height", 0);
    }
    item.file = numbered(type, ".h264");
  } else if (startsWith(bytes, {0xff, 0xd8})) {
    item.kind = LytroItemKind::Jpeg;
    if (parent && parent->contains("lambda") && (*parent)["lambda"].is_number())
      item.lambda = (*parent)["lambda"].get<double>();
    if (parent && parent->contains("focus") && (*parent)["focus"].is_number())
      item.lambda = (*parent)["focus"].get<double>();
    const bool thumbnail = ref.pointer.find("thumbnail") != std::string::npos;
    item.role = thumbnail ? "thumbnail (JPEG)" : "refocus-stack slice (JPEG)";
    item.file = numbered(thumbnail ? "thumbnail" : "slice", ".jpg");
  } else {
    item.kind = LytroItemKind::Component;
    item.role = "component named at " + ref.pointer;
    item.file = item.section->name + ".bin";
  }
}

}  // namespace

const char* lytroItemKindName(LytroItemKind kind) {
  switch (kind) {
    case LytroItemKind::TableOfContents: return "table of contents";
    case LytroItemKind::FrameMetadata: return "frame metadata";
    case LytroItemKind::PrivateMetadata: return "private metadata";
    case LytroItemKind::RawFrame: return "raw frame";
    case LytroItemKind::Jpeg: return "jpeg";
    case LytroItemKind::H264: return "h264";
    case LytroItemKind::DepthMap: return "depth map";
    case LytroItemKind::ConfidenceMap: return "confidence map";
    case LytroItemKind::Component: return "component";
  }
  return "?";
}

LytroContents describeLytroContainer(const LytroContainer& container) {
  LytroContents contents;
  std::map<const LytroSection*, LytroItem> bySection;
  std::map<std::string, int> counters;
  for (const LytroReference& ref : container.references()) {
    const LytroSection* section = container.find(ref.name);
    if (!section || bySection.count(section)) continue;  // named but absent (the raw of a processed file), or seen
    LytroItem item;
    item.section = section;
    classify(container.tableOfContents, ref, item, counters);
    bySection[section] = item;
  }
  bool tocSeen = false;
  int unnamed = 0;
  for (const LytroSection& section : container.sections) {
    if (section.kind == LytroSectionKind::Package) continue;
    auto it = bySection.find(&section);
    if (it != bySection.end()) {
      contents.items.push_back(it->second);
      continue;
    }
    LytroItem item;
    item.section = &section;
    if (section.kind == LytroSectionKind::Metadata && !tocSeen) {
      tocSeen = true;
      item.kind = LytroItemKind::TableOfContents;
      item.role = "table of contents (JSON)";
      item.file = "metadata.json";
    } else {
      item.role = "not named by the table of contents";
      item.file = section.name.empty() ? "section_" + std::to_string(unnamed++) + ".bin" : section.name + ".bin";
    }
    contents.items.push_back(item);
  }

  json summary = json::object();
  std::map<std::string, int> counts;
  for (const LytroItem& item : contents.items) ++counts[lytroItemKindName(item.kind)];
  summary["items"] = counts;
  // Key facts of the frame metadata, wherever it is (inline in Illum pictures, or a section).
  const json* metadata = findLytroFrameMetadata(container.tableOfContents);
  json fromSection;
  for (const LytroItem& item : contents.items)
    if (!metadata && item.kind == LytroItemKind::FrameMetadata) {
      fromSection = json::parse(item.section->payload.begin(), item.section->payload.end(), nullptr, false);
      if (!fromSection.is_discarded()) metadata = findLytroFrameMetadata(fromSection);
    }
  if (metadata) {
    auto format = parseLytroFrameMetadata(*metadata, "");
    if (format) {
      json facts = {{"sensor", {format->width, format->height}},
                    {"bits_per_pixel", rawPackingBits(format->packing)},
                    {"bayer", colorFilterName(format->colorFilter)},
                    {"black_level", format->blackLevel},
                    {"white_level", format->whiteLevel}};
      if (!format->camera.empty()) facts["camera"] = format->camera;
      if (format->lenslet)
        facts["lenslet"] = {{"pitch_px", format->lenslet->pitchPx},
                            {"rotation_rad", format->lenslet->rotationRad},
                            {"offset_px", format->lenslet->offsetPx},
                            {"packing", packingName(format->lenslet->packing)}};
      summary["frame"] = facts;
    }
  }
  contents.summary = summary;
  return contents;
}

std::optional<Image> floatMap(const LytroItem& item) {
  const std::vector<std::uint8_t>& bytes = item.section->payload;
  const std::size_t pixels = std::size_t(std::max(item.width, 0)) * std::size_t(std::max(item.height, 0));
  if (item.width <= 0 || item.height <= 0 || checkedProduct({pixels, 4}) != std::uint64_t(bytes.size()))
    return std::nullopt;
  Image map(item.width, item.height, 1);
  for (std::size_t k = 0; k < pixels; ++k) {
    const std::uint32_t bits = std::uint32_t(bytes[4 * k]) | std::uint32_t(bytes[4 * k + 1]) << 8 |
                               std::uint32_t(bytes[4 * k + 2]) << 16 | std::uint32_t(bytes[4 * k + 3]) << 24;
    float v;
    std::memcpy(&v, &bits, 4);
    map.pixels()[k] = v;
  }
  return map;
}

Result<LytroRefocusStack> readLytroRefocusStack(const std::filesystem::path& path) {
  LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(path));
  const LytroContents contents = describeLytroContainer(container);
  LytroRefocusStack stack;
  for (const LytroItem& item : contents.items) {
    if (item.kind == LytroItemKind::Jpeg && item.lambda && std::isfinite(*item.lambda))
      stack.slices.push_back({*item.lambda, item.section->payload});
    if (item.kind == LytroItemKind::DepthMap && stack.depth.empty())
      if (auto map = floatMap(item)) stack.depth = std::move(*map);
  }
  if (stack.slices.size() < 2)
    return makeError(ErrorCode::Format, path.string() + ": no refocus stack of JPEG slices in this Lytro container (" +
                                            std::to_string(stack.slices.size()) +
                                            " found; a raw frame needs --white; `lfcam extract` lists what it holds)");
  std::sort(stack.slices.begin(), stack.slices.end(),
            [](const LytroRefocusSlice& a, const LytroRefocusSlice& b) { return a.lambda < b.lambda; });
  for (float v : stack.depth.pixels())
    if (!std::isfinite(v)) return makeError(ErrorCode::Format, path.string() + ": the depth map has non-finite values");
  return stack;
}

Status extractLytroContainer(const LytroContainer& container, const std::filesystem::path& folder,
                             const std::string& where) {
  const LytroContents contents = describeLytroContainer(container);
  // Decode everything that can fail before anything is written.
  std::optional<RawImage> raw;
  for (const LytroItem& item : contents.items)
    if (item.kind == LytroItemKind::RawFrame) {
      LFCAM_ASSIGN_OR_RETURN(auto read, rawFromLytroContainer(container, where));
      raw = std::move(read);
    }
  return writeFolderAtomically(folder, [&](const std::filesystem::path& dir) -> Status {
    json index = json::array();
    for (const LytroItem& item : contents.items) {
      const std::vector<std::uint8_t>& bytes = item.section->payload;
      json entry = {{"section", item.section->name},
                    {"kind", lytroItemKindName(item.kind)},
                    {"role", item.role},
                    {"bytes", bytes.size()}};
      if (item.width) entry["size"] = {item.width, item.height};
      if (item.lambda) entry["lambda"] = *item.lambda;
      std::vector<std::string> files;
      switch (item.kind) {
        case LytroItemKind::TableOfContents:
        case LytroItemKind::FrameMetadata:
        case LytroItemKind::PrivateMetadata: {
          const json parsed = json::parse(bytes.begin(), bytes.end(), nullptr, false);
          if (parsed.is_discarded()) {
            LFCAM_TRY(writeBytes(dir / (item.section->name + ".bin"), bytes.data(), bytes.size()));
            files.push_back(item.section->name + ".bin");
          } else {
            LFCAM_TRY(writeText(dir / item.file, parsed.dump(2) + "\n"));
            files.push_back(item.file);
          }
          break;
        }
        case LytroItemKind::RawFrame: {
          Image codes = raw->mosaic.copy();
          for (float& v : codes.pixels()) v /= 65535.0f;
          ImageWriteOptions options;
          options.sampleType = SampleType::UInt16;
          options.description = "lfcam extract: raw sensor frame, 16-bit codes are DN";
          LFCAM_TRY(writeImage(dir / item.file, codes, options));
          files.push_back(item.file);
          break;
        }
        case LytroItemKind::DepthMap:
        case LytroItemKind::ConfidenceMap: {
          const std::optional<Image> map = floatMap(item);
          if (!map) {
            // Size unknown or not float32: keep the bytes.
            LFCAM_TRY(writeBytes(dir / (item.file + ".bin"), bytes.data(), bytes.size()));
            files.push_back(item.file + ".bin");
            break;
          }
          LFCAM_TRY(writeImage(dir / (item.file + ".pfm"), *map));
          LFCAM_TRY(writeImage(dir / (item.file + ".png"), colorMap(*map)));
          files.push_back(item.file + ".pfm");
          files.push_back(item.file + ".png");
          break;
        }
        default: LFCAM_TRY(writeBytes(dir / item.file, bytes.data(), bytes.size())); files.push_back(item.file);
      }
      entry["files"] = files;
      index.push_back(entry);
    }
    return writeText(dir / "index.json",
                     json{{"source", where}, {"summary", contents.summary}, {"items", index}}.dump(2) + "\n");
  });
}

}  // namespace lfcam
