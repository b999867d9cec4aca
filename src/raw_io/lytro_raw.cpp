// Raw frames in Lytro containers (raw_io.hpp): reading the frame the table of contents names, and
// writing simulated captures with real-style metadata.
#include <cmath>
#include <limits>
#include <numbers>

#include "core/memory_budget.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/lytro_metadata.hpp"
#include "raw_io/lytro_raw.hpp"
#include "raw_io/lytro_setting.hpp"

namespace lfcam {

namespace {

using nlohmann::json;

// The "frame" object of the table of contents: picture.frameArray[0].frame (first generation),
// frames[0].frame (Illum), master.picture.frameArray[0].frame (white-image files).
const json* tocFrame(const json& toc) {
  for (const char* pointer : {"/picture/frameArray/0/frame", "/frames/0/frame", "/master/picture/frameArray/0/frame"}) {
    const json::json_pointer p(pointer);
    if (toc.contains(p) && toc.at(p).is_object()) return &toc.at(p);
  }
  return nullptr;
}

std::string refString(const json& frame, const char* key) {
  auto it = frame.find(key);
  return it != frame.end() && it->is_string() ? it->get<std::string>() : std::string();
}

// The pixels of a packed frame as `metadata` (the frame's, or a document wrapping it) describes them;
// `name` is the frame's in messages.
Result<RawImage> rawFromPackedFrame(std::span<const std::uint8_t> bytes, const json& document, const std::string& name,
                                    const std::string& where) {
  const json* found = findLytroFrameMetadata(document);
  const json& metadata = found ? *found : document;  // parsing names what is missing
  LFCAM_ASSIGN_OR_RETURN(auto format, parseLytroFrameMetadata(metadata, where));
  const std::size_t pixels = std::size_t(format.width) * std::size_t(format.height);
  const std::size_t needed = *packedByteCount(format.packing, pixels);  // width, height <= 1e5: no overflow
  if (bytes.size() < needed)
    return makeError(ErrorCode::Format, where + ": raw frame" + (name.empty() ? "" : " " + name) + " has " +
                                            std::to_string(bytes.size()) + " bytes; " + std::to_string(format.width) +
                                            "x" + std::to_string(format.height) + " pixels of " +
                                            std::to_string(rawPackingBits(format.packing)) + " bits need " +
                                            std::to_string(needed));
  LFCAM_TRY(checkMemory(where, checkedProduct({pixels, sizeof(float) + sizeof(std::uint16_t)}), "the raw frame"));
  RawImage raw;
  std::vector<std::uint16_t> samples(pixels);
  unpackRaw(format.packing, bytes, samples);
  raw.mosaic = Image(format.width, format.height, 1);
  float* out = raw.mosaic.plane(0);
  for (std::size_t k = 0; k < pixels; ++k) out[k] = samples[k];
  raw.colorFilter = format.colorFilter;
  raw.blackLevel = format.blackLevel;
  raw.whiteLevel = format.whiteLevel;
  raw.lenslet = format.lenslet;
  raw.whiteBalance = format.whiteBalance;
  raw.colorMatrix = format.colorMatrix;
  raw.metadataJson = metadata.dump();
  return raw;
}

}  // namespace

Result<RawImage> rawFromLytroCaldata(std::span<const std::uint8_t> pixels, const json& description,
                                     const std::string& where) {
  LFCAM_ASSIGN_OR_RETURN(auto raw, rawFromPackedFrame(pixels, description, "", where));
  raw.setting = lytroCameraSetting(description, nullptr);
  raw.source = "lytro-caldata";
  return raw;
}

Result<RawImage> rawFromLytroContainer(const LytroContainer& container, const std::string& where) {
  const json* frame = container.tableOfContents.is_null() ? nullptr : tocFrame(container.tableOfContents);
  const LytroSection* image = frame ? container.find(refString(*frame, "imageRef")) : nullptr;
  if (!image)
    return makeError(ErrorCode::Unsupported, where +
                                                 ": holds no raw sensor frame (a processed picture: see `lfcam info` "
                                                 "and `lfcam extract`)");
  json metadata;
  if (const LytroSection* section = container.find(refString(*frame, "metadataRef"))) {
    metadata = json::parse(section->payload.begin(), section->payload.end(), nullptr, false);
    if (metadata.is_discarded())
      return makeError(ErrorCode::Format,
                       where + ": the frame metadata section " + section->name + " is not valid JSON");
  } else if (frame->contains("metadata")) {
    metadata = (*frame)["metadata"];
  } else {
    return makeError(ErrorCode::Format, where + ": the raw frame has no metadata (metadataRef names no section)");
  }
  json privateMetadata;
  if (const LytroSection* section = container.find(refString(*frame, "privateMetadataRef")))
    privateMetadata = json::parse(section->payload.begin(), section->payload.end(), nullptr, false);
  LFCAM_ASSIGN_OR_RETURN(auto raw, rawFromPackedFrame(image->payload, metadata, image->name, where));
  raw.setting = lytroCameraSetting(metadata, privateMetadata.is_object() ? &privateMetadata : nullptr);
  raw.source = container.tableOfContents.contains("frames") ? "lytro-lfr" : "lytro-lfp";
  raw.metadataJson = metadata.dump();
  return raw;
}

Result<LytroContainer> makeLytroRawContainer(const RawImage& raw, const LytroWriteOptions& options,
                                             const std::string& where) {
  const Image& mosaic = raw.mosaic;
  if (mosaic.empty() || mosaic.channels() != 1)
    return makeError(ErrorCode::Usage, where + ": a raw frame needs a one-channel mosaic");
  std::vector<std::uint16_t> samples(mosaic.planeSize());
  float largest = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const float v = mosaic.plane(0)[k];
    if (!(v >= 0 && v <= 65535 && v == std::floor(v)))
      return makeError(ErrorCode::Usage,
                       where + ": raw values must be whole DN in [0, 65535], found " + std::to_string(v));
    samples[k] = std::uint16_t(v);
    largest = std::max(largest, v);
  }
  const double top = std::max<double>(largest, raw.whiteLevel);
  LytroFrameFormat format;
  format.width = mosaic.width();
  format.height = mosaic.height();
  if (options.style == LytroStyle::FirstGeneration)
    format.packing = top <= 4095 ? RawPacking::Bits12BigEndian : RawPacking::Bits16LittleEndian;
  else
    format.packing = top <= 1023 ? RawPacking::Bits10LittleEndian : RawPacking::Bits16LittleEndian;
  format.colorFilter = raw.colorFilter;
  format.blackLevel = raw.blackLevel;
  format.whiteLevel = raw.whiteLevel;
  format.pixelPitchM = options.pixelPitchMm * 1e-3;
  format.lenslet = raw.lenslet;
  format.whiteBalance = raw.whiteBalance;
  format.colorMatrix = raw.colorMatrix;
  json metadata = makeLytroFrameMetadata(format, options.style);
  if (!options.extraJson.empty()) {
    json extra = json::parse(options.extraJson, nullptr, false);
    if (extra.is_discarded()) return makeError(ErrorCode::Usage, where + ": the extra metadata is not JSON");
    metadata["lfcam"] = std::move(extra);
  }

  const CameraSetting& setting = options.setting;
  if (setting.zoomStep) metadata["devices"]["lens"]["zoomStep"] = *setting.zoomStep;
  if (setting.focusStep) metadata["devices"]["lens"]["focusStep"] = *setting.focusStep;
  if (setting.exposureS) metadata["devices"]["shutter"]["frameExposureDuration"] = *setting.exposureS;

  LytroSection image = makeLytroSection(LytroSectionKind::Component, packRaw(format.packing, samples));
  LytroSection meta = makeLytroSection(LytroSectionKind::Component, metadata.dump(1));
  LytroSection privateMeta = makeLytroSection(
      LytroSectionKind::Component,
      json{{"camera", {{"serialNumber", setting.serial.empty() ? "lfcam-simulator" : setting.serial}}}}.dump(1));
  json frame = {
      {"frame", {{"metadataRef", meta.name}, {"privateMetadataRef", privateMeta.name}, {"imageRef", image.name}}},
      {"parameters",
       {{"vendorContent",
         {{"com.lytro.tags", {{"darkFrame", false}, {"modulationFrame", options.modulationFrame}}}}}}}};
  json toc;
  if (options.style == LytroStyle::FirstGeneration) {
    toc = {{"picture",
            {{"frameArray", {frame}},
             {"viewArray", json::array()},
             {"accelerationArray", json::array()},
             {"derivationArray", json::array()}}},
           {"thumbnailArray", json::array()},
           {"version", {{"major", 1}, {"minor", 0}, {"provisionalDate", "2011-08-03"}}}};
  } else {
    toc = {{"schema", "http://schema.lytro.com/lfp/picture/2.1.6/picture_schema.json"},
           {"generators", {"lfcam"}},
           {"thumbnails", json::array()},
           {"derivations", json::array()},
           {"frames", {frame}},
           {"views", json::array()},
           {"annotations", json::array()}};
  }
  std::vector<LytroSection> components;
  components.push_back(std::move(meta));
  components.push_back(std::move(privateMeta));
  components.push_back(std::move(image));
  return makeLytroContainer(toc, std::move(components));
}

Status writeLytroRaw(const std::filesystem::path& path, const RawImage& raw, const LytroWriteOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto container, makeLytroRawContainer(raw, options, path.string()));
  return writeLytroContainer(path, container);
}

Status writeSimulationContainers(const std::filesystem::path& folder, LytroStyle style) {
  const std::string extension = style == LytroStyle::FirstGeneration ? ".lfp" : ".lfr";
  for (const char* stem : {"raw", "white"}) {
    std::filesystem::path source;
    for (const char* ext : {".png", ".tiff", ".tif"})
      if (std::filesystem::exists(folder / (std::string(stem) + ext))) source = folder / (std::string(stem) + ext);
    if (source.empty()) {
      if (std::string(stem) == "raw") return makeError(ErrorCode::Io, (folder / "raw.png").string() + ": no such file");
      continue;  // --no-white
    }
    // The first generation's white images came with the desktop software, not in picture files:
    // only the Illum style gets a white container (its MOD_*.RAW equivalent).
    if (std::string(stem) == "white" && style == LytroStyle::FirstGeneration) continue;
    LFCAM_ASSIGN_OR_RETURN(auto raw, readRaw(source));
    if (raw.source != "simulator")
      return makeError(ErrorCode::Format,
                       (folder / "camera.json").string() + ": missing or not for " + source.string());
    LytroWriteOptions options;
    options.style = style;
    options.modulationFrame = std::string(stem) == "white";
    const json camera = json::parse(raw.metadataJson, nullptr, false);
    const json sensor = camera.is_object() ? camera.value("sensor", json()) : json();
    if (sensor.is_object() && sensor.contains("pixel_pitch_mm") && sensor["pixel_pitch_mm"].is_number())
      options.pixelPitchMm = sensor["pixel_pitch_mm"].get<double>();
    options.extraJson = raw.metadataJson;
    LFCAM_TRY(writeLytroRaw(folder / (std::string(stem) + extension), raw, options));
  }
  return {};
}

}  // namespace lfcam
