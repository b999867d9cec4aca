// readRaw (raw_io.hpp): dispatch by content, and the image-file path with camera.json.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "io/io_support.hpp"
#include "io/tiff_file.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "raw_io/libraw_read.hpp"
#include "raw_io/lytro_container.hpp"
#include "raw_io/lytro_raw.hpp"

namespace lfcam {

namespace {

// Extensions LibRaw is asked first about: many are TIFF inside and would pass for images.
bool hasCameraRawExtension(const std::filesystem::path& path) {
  const std::string ext = io::lowerExtension(path);
  static const char* known[] = {".dng", ".cr2", ".cr3", ".crw", ".nef", ".nrw", ".arw", ".srf",
                                ".sr2", ".orf", ".rw2", ".raf", ".pef", ".srw", ".3fr", ".erf",
                                ".kdc", ".dcr", ".mrw", ".mos", ".iiq", ".rwl", ".x3f"};
  return std::any_of(std::begin(known), std::end(known), [&](const char* k) { return ext == k; });
}

// The optics of a simulator capture: its light field's steps and its main lens.
std::optional<Optics> opticsFromCameraJson(const nlohmann::json& camera) {
  const nlohmann::json lf = camera.value("light_field", nlohmann::json()),
                       lens = camera.value("main_lens", nlohmann::json());
  auto number = [](const nlohmann::json& o, const char* key) {
    return o.is_object() && o.contains(key) && o[key].is_number() ? o[key].get<double>() : 0.0;
  };
  Optics optics;
  optics.lensStepMm = number(lf, "lens_step_mm");
  optics.spatialStepMm = number(lf, "spatial_step_mm");
  optics.lensToMicrolensMm = number(lens, "image_distance_mm");
  if (number(lens, "focal_length_mm") > 0) optics.focalLengthMm = number(lens, "focal_length_mm");
  if (optics.lensStepMm <= 0 || optics.spatialStepMm <= 0 || optics.lensToMicrolensMm <= 0) return std::nullopt;
  return optics;
}

// camera.json written by `lfcam simulate` beside the image, when it describes this sensor.
void applyCameraJson(const std::filesystem::path& path, RawImage& raw) {
  const std::filesystem::path file = path.parent_path() / "camera.json";
  std::ifstream in(file);
  if (!in) return;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.is_object() || json.value("lfcam_format", "") != "lfcam-simulated-camera") return;
  const nlohmann::json& sensor = json.value("sensor", nlohmann::json::object());
  if (!sensor.is_object() || sensor.value("width", -1) != raw.mosaic.width() ||
      sensor.value("height", -1) != raw.mosaic.height())
    return;
  if (sensor.contains("black_level") && sensor["black_level"].is_number())
    raw.blackLevel = sensor["black_level"].get<double>();
  if (sensor.contains("white_level") && sensor["white_level"].is_number())
    raw.whiteLevel = sensor["white_level"].get<double>();
  if (sensor.contains("color_filter") && sensor["color_filter"].is_string())
    if (auto filter = parseColorFilterName(sensor["color_filter"].get<std::string>())) raw.colorFilter = *filter;
  const nlohmann::json lattice = json.value("lattice_px", nlohmann::json());
  if (lattice.is_object() && lattice.contains("pitch_px") && lattice["pitch_px"].is_number()) {
    LensletHint hint;
    hint.pitchPx = lattice["pitch_px"].get<double>();
    hint.rotationRad = lattice.value("rotation_deg", 0.0) * std::numbers::pi / 180.0;
    const nlohmann::json offset = lattice.value("offset_px", nlohmann::json::array());
    if (offset.is_array() && offset.size() == 2 && offset[0].is_number() && offset[1].is_number())
      hint.offsetPx = {offset[0].get<double>(), offset[1].get<double>()};
    hint.packing = lattice.value("packing", "square") == "hexagonal" ? Packing::Hexagonal : Packing::Square;
    raw.lenslet = hint;
  }
  raw.optics = opticsFromCameraJson(json);
  raw.source = "simulator";
  raw.metadataJson = json.dump();
}

// A side-car <stem>.json beside an image naming its camera and lens setting (docs/formats.md, "White
// images"): what picks a white from a database for a camera that is not a Lytro.
Status applySideCar(const std::filesystem::path& path, RawImage& raw) {
  std::filesystem::path file = path;
  file.replace_extension(".json");
  std::ifstream in(file);
  if (!in) return {};
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.is_object() || !json.contains("serial")) return {};
  CameraSetting& setting = raw.setting;
  if (!json["serial"].is_string()) return makeError(ErrorCode::Format, file.string() + ": serial: expected a string");
  setting.serial = json["serial"].get<std::string>();
  for (const auto& [key, value] :
       {std::pair{"zoom_step", &setting.zoomStep}, std::pair{"focus_step", &setting.focusStep},
        std::pair{"exposure_s", &setting.exposureS}}) {
    if (!json.contains(key)) continue;
    if (!json[key].is_number()) return makeError(ErrorCode::Format, file.string() + ": " + key + ": expected a number");
    *value = json[key].get<double>();
  }
  setting.model = json.value("model", "");
  setting.metadataKeys = "side-car";
  return {};
}

// A bare packed frame (Lytro calibration data's MOD_*.RAW) described by the .TXT of the same name.
std::optional<std::filesystem::path> caldataDescription(const std::filesystem::path& path) {
  if (io::lowerExtension(path) != ".raw") return std::nullopt;
  for (const char* ext : {".TXT", ".txt"}) {
    std::filesystem::path partner = path;
    partner.replace_extension(ext);
    if (std::filesystem::is_regular_file(partner)) return partner;
  }
  return std::nullopt;
}

Result<RawImage> readCaldataRaw(const std::filesystem::path& path, const std::filesystem::path& description) {
  LFCAM_ASSIGN_OR_RETURN(auto text, readFileBytes(description, kMaxLytroFileBytes));
  const nlohmann::json json = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (json.is_discarded()) return makeError(ErrorCode::Format, description.string() + ": not JSON");
  LFCAM_ASSIGN_OR_RETURN(auto pixels, readFileBytes(path, kMaxLytroFileBytes));
  return rawFromLytroCaldata(pixels, json, path.string());
}

Result<RawImage> readImageRaw(const std::filesystem::path& path, const RawReadOptions& options) {
  LFCAM_ASSIGN_OR_RETURN(auto header, readImageHeader(path));
  LFCAM_ASSIGN_OR_RETURN(auto image, readImage(path));
  const int colors = image.channels() == 2 || image.channels() == 4 ? image.channels() - 1 : image.channels();
  RawImage raw;
  raw.mosaic = Image(image.width(), image.height(), 1);
  // Back to the file's codes: 8-bit files were sRGB-decoded by readImage (exactly invertible),
  // 16-bit ones scaled by 1/65535. Colour lenslet images become their channels' mean.
  const SampleType type = header.sampleType;
  float* out = raw.mosaic.plane(0);
  for (std::size_t k = 0; k < raw.mosaic.planeSize(); ++k) {
    double sum = 0;
    for (int c = 0; c < colors; ++c) {
      const float v = image.plane(c)[k];
      sum += type == SampleType::UInt8    ? std::round(srgbFromLinear(v) * 255.0)
             : type == SampleType::UInt16 ? std::round(double(v) * 65535.0)
                                          : double(v);
    }
    out[k] = float(sum / colors);
  }
  raw.blackLevel = 0;
  raw.whiteLevel = type == SampleType::UInt8 ? 255.0 : type == SampleType::UInt16 ? 65535.0 : 1.0;
  const io::TiffLevels tags = io::readTiffLevels(path);
  if (tags.black) raw.blackLevel = *tags.black;
  if (tags.white) raw.whiteLevel = *tags.white;
  raw.source = "image";
  if (options.useCameraJson) applyCameraJson(path, raw);
  LFCAM_TRY(applySideCar(path, raw));
  return raw;
}

// A black level at or above every sample would leave nothing once subtracted: a mistake (a level
// in the wrong units, a wrong file), refused rather than decoded into a black light field.
Status checkBlackLevelAgainstData(const std::filesystem::path& path, const RawImage& raw, ErrorCode code,
                                  const std::string& given) {
  float largest = 0;
  for (const float value : raw.mosaic.pixels()) largest = std::max(largest, value);
  if (raw.blackLevel < largest) return {};
  return makeError(code, path.string() + ": black level " + io::shortestNumber(raw.blackLevel) + " DN (" + given +
                             ") is not below the largest value in the file, " + io::shortestNumber(largest) +
                             " DN: every sample would be black");
}

}  // namespace

std::optional<ColorFilter> parseColorFilterName(std::string_view name) {
  std::string upper(name);
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  if (upper == "RGGB") return ColorFilter::RGGB;
  if (upper == "BGGR") return ColorFilter::BGGR;
  if (upper == "GRBG") return ColorFilter::GRBG;
  if (upper == "GBRG") return ColorFilter::GBRG;
  if (upper == "MONO" || upper == "MONOCHROME") return ColorFilter::Mono;
  return std::nullopt;
}

Result<RawImage> readRaw(const std::filesystem::path& path, const RawReadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return makeError(ErrorCode::Io, path.string() + ": no such file");
  if (std::filesystem::is_directory(path, ec))
    return makeError(ErrorCode::Usage, path.string() + ": is a folder, expected a raw image file");
  Result<RawImage> raw = makeError(ErrorCode::Format, "");
  if (looksLikeLytroContainer(path)) {
    LFCAM_ASSIGN_OR_RETURN(auto container, readLytroContainer(path));
    raw = rawFromLytroContainer(container, path.string());
  } else if (const auto description = caldataDescription(path)) {
    raw = readCaldataRaw(path, *description);
  } else if (hasCameraRawExtension(path) || !looksLikeImageFile(path)) {
    raw = readCameraRaw(path);
    if (!raw && !hasCameraRawExtension(path))
      return makeError(ErrorCode::Format, path.string() +
                                              ": not a raw image lfcam reads (Lytro container, PNG/TIFF lenslet "
                                              "image or camera raw)");
  } else {
    raw = readImageRaw(path, options);
  }
  LFCAM_TRY(raw);
  if (options.colorFilter) raw->colorFilter = *options.colorFilter;
  if (options.blackLevel) {
    if (!(*options.blackLevel >= 0) || !std::isfinite(*options.blackLevel))
      return makeError(ErrorCode::Usage, path.string() + ": black level " + io::shortestNumber(*options.blackLevel) +
                                             " DN must be a finite number of at least 0");
    raw->blackLevel = *options.blackLevel;
  }
  if (options.whiteLevel) raw->whiteLevel = *options.whiteLevel;
  // Levels the caller gave are its usage; levels the file gave are the file's fault.
  const ErrorCode code = options.blackLevel || options.whiteLevel ? ErrorCode::Usage : ErrorCode::Format;
  if (!(raw->whiteLevel > raw->blackLevel))
    return makeError(code, path.string() + ": black level " + io::shortestNumber(raw->blackLevel) +
                               " DN must be below the white level " + io::shortestNumber(raw->whiteLevel) + " DN");
  if (options.blackLevel) LFCAM_TRY(checkBlackLevelAgainstData(path, *raw, ErrorCode::Usage, "as given"));
  return raw;
}

}  // namespace lfcam
