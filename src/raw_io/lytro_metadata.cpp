// Lytro frame metadata (lytro_metadata.hpp).
#include "raw_io/lytro_metadata.hpp"

#include <cmath>

namespace lfcam {

namespace {

using nlohmann::json;

const json* child(const json* j, const char* key) {
  if (!j || !j->is_object()) return nullptr;
  auto it = j->find(key);
  return it == j->end() ? nullptr : &*it;
}

const json* path(const json* j, std::initializer_list<const char*> keys) {
  for (const char* key : keys) j = child(j, key);
  return j;
}

const json* firstFrame(const json* array) {
  if (!array || !array->is_array() || array->empty()) return nullptr;
  return path(&(*array)[0], {"frame", "metadata"});
}

std::optional<double> number(const json* j) {
  if (!j || !j->is_number()) return std::nullopt;
  const double v = j->get<double>();
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

// A level given per Bayer channel ({"r", "gr", "gb", "b"}) or as one number: the mean.
std::optional<double> level(const json* j) {
  if (auto v = number(j)) return v;
  if (!j || !j->is_object()) return std::nullopt;
  double sum = 0;
  int count = 0;
  for (const char* key : {"r", "gr", "gb", "b"})
    if (auto v = number(child(j, key))) sum += *v, ++count;
  if (count == 0) return std::nullopt;
  return sum / count;
}

std::optional<std::array<double, 9>> matrix(const json* j) {
  if (!j || !j->is_array() || j->size() != 9) return std::nullopt;
  std::array<double, 9> m{};
  for (std::size_t k = 0; k < 9; ++k) {
    auto v = number(&(*j)[k]);
    if (!v) return std::nullopt;
    m[k] = *v;
  }
  return m;
}

json perChannel(double value) { return {{"r", value}, {"gr", value}, {"gb", value}, {"b", value}}; }

json mosaicJson(ColorFilter filter) {
  const char* upperLeft = "r";
  switch (filter) {
    case ColorFilter::RGGB: upperLeft = "r"; break;
    case ColorFilter::BGGR: upperLeft = "b"; break;
    case ColorFilter::GRBG: upperLeft = "gr"; break;
    case ColorFilter::GBRG: upperLeft = "gb"; break;
    case ColorFilter::Mono: return {{"tile", "monochrome"}, {"upperLeftPixel", "gr"}};
  }
  return {{"tile", "r,gr:gb,b"}, {"upperLeftPixel", upperLeft}};
}

}  // namespace

const json* findLytroFrameMetadata(const json& document) {
  if (!document.is_object()) return nullptr;
  if (document.contains("image")) return &document;
  for (const json* candidate :
       {firstFrame(path(&document, {"master", "picture", "frameArray"})),
        firstFrame(path(&document, {"picture", "frameArray"})), firstFrame(path(&document, {"frames"}))})
    if (candidate && candidate->is_object() && candidate->contains("image")) return candidate;
  return nullptr;
}

std::optional<ColorFilter> lytroMosaicFilter(const json& mosaic) {
  const json* tile = child(&mosaic, "tile");
  const json* upperLeft = child(&mosaic, "upperLeftPixel");
  if (!tile || !tile->is_string()) return std::nullopt;
  if (*tile == "monochrome") return ColorFilter::Mono;
  if (*tile != "r,gr:gb,b" || !upperLeft || !upperLeft->is_string()) return std::nullopt;
  // The tile r,gr:gb,b read from the named corner.
  if (*upperLeft == "r") return ColorFilter::RGGB;
  if (*upperLeft == "gr") return ColorFilter::GRBG;
  if (*upperLeft == "gb") return ColorFilter::GBRG;
  if (*upperLeft == "b") return ColorFilter::BGGR;
  return std::nullopt;
}

Result<LytroFrameFormat> parseLytroFrameMetadata(const json& metadata, const std::string& where) {
  const json* image = child(&metadata, "image");
  if (!image) return makeError(ErrorCode::Format, where + ": frame metadata without \"image\"");
  const json* raw = child(image, "rawDetails");
  const json* details = raw ? raw : image;  // F01 style : Illum "lightning" style
  LytroFrameFormat f;
  const auto width = number(child(image, "width")), height = number(child(image, "height"));
  if (!width || !height || *width < 1 || *height < 1 || *width > 100000 || *height > 100000 ||
      *width != std::floor(*width) || *height != std::floor(*height))
    return makeError(ErrorCode::Format, where + ": image.width and image.height must be whole numbers in [1, 100000]");
  f.width = int(*width);
  f.height = int(*height);

  const json* packing = child(details, "pixelPacking");
  const auto bits = number(child(packing, "bitsPerPixel"));
  const json* endianness = child(packing, "endianness");
  if (!bits || !endianness || !endianness->is_string())
    return makeError(ErrorCode::Format, where + ": no pixelPacking (bitsPerPixel, endianness) in the frame metadata");
  const std::string endian = endianness->get<std::string>();
  if (*bits == 12 && endian == "big")
    f.packing = RawPacking::Bits12BigEndian;
  else if (*bits == 10 && endian == "little")
    f.packing = RawPacking::Bits10LittleEndian;
  else if (*bits == 16 && endian == "little")
    f.packing = RawPacking::Bits16LittleEndian;
  else
    return makeError(ErrorCode::Unsupported, where + ": pixel packing of " + std::to_string(int(*bits)) + " bits " +
                                                 endian + "-endian (lfcam reads 12-bit big, 10-bit and 16-bit little)");

  const json* mosaic = child(details, "mosaic");
  if (!mosaic) mosaic = path(&metadata, {"devices", "sensor", "mosaic"});
  if (mosaic) {
    auto filter = lytroMosaicFilter(*mosaic);
    if (!filter) return makeError(ErrorCode::Unsupported, where + ": unknown mosaic " + mosaic->dump());
    f.colorFilter = *filter;
  }
  const json* format = child(details, "pixelFormat");
  f.whiteLevel = level(child(format, "white")).value_or(double((1 << rawPackingBits(f.packing)) - 1));
  f.blackLevel = level(child(format, "black")).value_or(0.0);
  if (f.whiteLevel <= f.blackLevel)
    return makeError(ErrorCode::Format, where + ": white level " + std::to_string(f.whiteLevel) +
                                            " is not above the black level " + std::to_string(f.blackLevel));

  const json* color = child(image, "color");
  f.colorMatrix = matrix(child(color, "ccmRgbToSrgbArray"));
  if (!f.colorMatrix) f.colorMatrix = matrix(child(color, "ccm"));
  if (const json* gain = child(color, "whiteBalanceGain")) {
    auto r = number(child(gain, "r")), gr = number(child(gain, "gr")), gb = number(child(gain, "gb")),
         b = number(child(gain, "b"));
    if (r && gr && gb && b) f.whiteBalance = std::array<double, 3>{*r, 0.5 * (*gr + *gb), *b};
  }

  f.pixelPitchM = number(path(&metadata, {"devices", "sensor", "pixelPitch"}));
  const json* mla = path(&metadata, {"devices", "mla"});
  const auto lensPitch = number(child(mla, "lensPitch"));
  if (f.pixelPitchM && *f.pixelPitchM > 0 && lensPitch && *lensPitch > 0) {
    LensletHint hint;
    hint.pitchPx = *lensPitch / *f.pixelPitchM;
    hint.rotationRad = number(child(mla, "rotation")).value_or(0.0);
    const json* offset = child(mla, "sensorOffset");
    hint.offsetPx = {number(child(offset, "x")).value_or(0.0) / *f.pixelPitchM,
                     number(child(offset, "y")).value_or(0.0) / *f.pixelPitchM};
    const json* tiling = child(mla, "tiling");
    hint.packing = tiling && tiling->is_string() && tiling->get<std::string>().rfind("hex", 0) == 0 ? Packing::Hexagonal
                                                                                                    : Packing::Square;
    f.lenslet = hint;
  }
  const json* make = path(&metadata, {"camera", "make"});
  const json* model = path(&metadata, {"camera", "model"});
  if (make && make->is_string()) f.camera = make->get<std::string>();
  if (model && model->is_string()) f.camera += (f.camera.empty() ? "" : " ") + model->get<std::string>();
  return f;
}

json makeLytroFrameMetadata(const LytroFrameFormat& f, LytroStyle style) {
  const bool bigEndian = f.packing == RawPacking::Bits12BigEndian;
  const int bits = rawPackingBits(f.packing);
  const json pixelFormat = {
      {"rightShift", 0}, {"black", perChannel(f.blackLevel)}, {"white", perChannel(f.whiteLevel)}};
  const json pixelPacking = {{"endianness", bigEndian ? "big" : "little"}, {"bitsPerPixel", bits}};
  const std::array<double, 3> wb = f.whiteBalance.value_or(std::array<double, 3>{1, 1, 1});
  const std::array<double, 9> ccm = f.colorMatrix.value_or(std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
  json color = {{"whiteBalanceGain", {{"r", wb[0]}, {"gr", wb[1]}, {"gb", wb[1]}, {"b", wb[2]}}}};
  json image = {{"width", f.width}, {"height", f.height}, {"orientation", 1}, {"representation", "rawPacked"}};
  if (style == LytroStyle::FirstGeneration) {
    color["ccmRgbToSrgbArray"] = ccm;
    color["gamma"] = 0.41666001081466675;
    image["rawDetails"] = {
        {"pixelFormat", pixelFormat}, {"pixelPacking", pixelPacking}, {"mosaic", mosaicJson(f.colorFilter)}};
  } else {
    color["ccm"] = ccm;
    image["pixelFormat"] = pixelFormat;
    image["pixelPacking"] = pixelPacking;
    image["mosaic"] = mosaicJson(f.colorFilter);
    image["originOnSensor"] = {{"x", 0}, {"y", 0}};
  }
  image["color"] = color;
  json devices = {{"sensor", {{"bitsPerPixel", bits}, {"mosaic", mosaicJson(f.colorFilter)}}}};
  if (f.pixelPitchM) devices["sensor"]["pixelPitch"] = *f.pixelPitchM;
  if (f.lenslet && f.pixelPitchM) {
    const LensletHint& h = *f.lenslet;
    devices["mla"] = {
        {"tiling", h.packing == Packing::Hexagonal ? "hexUniformRowMajor" : "squareUniformRowMajor"},
        {"lensPitch", h.pitchPx * *f.pixelPitchM},
        {"rotation", h.rotationRad},
        {"defectArray", json::array()},
        {"config", "lfcam.simulated"},
        {"scaleFactor", {{"x", 1}, {"y", 1}}},
        {"sensorOffset", {{"x", h.offsetPx[0] * *f.pixelPitchM}, {"y", h.offsetPx[1] * *f.pixelPitchM}, {"z", 0}}}};
  }
  json out = {{"type", "lightField"}, {"image", image}, {"devices", devices}};
  out["camera"] = {{"make", "lfcam"},
                   {"model", style == LytroStyle::FirstGeneration ? "F01 (simulated)" : "ILLUM (simulated)"}};
  if (style == LytroStyle::Illum) {
    out["schema"] = "http://schema.lytro.com/lfp/lytro_illum_public/1.3.4/lytro_illum_public_schema.json";
    out["generator"] = "lfcam";
  }
  return out;
}

}  // namespace lfcam
