#include "lfcam/lfm/optics.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <utility>

#include "lfm/message_text.hpp"

namespace lfcam {

using lfm::number;
using lfm::usage;

double LfmOptics::rowPitchUm() const {
  return array == MicrolensLayout::Hexagonal ? microlensPitchUm * std::sqrt(3.0) / 2 : microlensPitchUm;
}

const char* microlensLayoutName(MicrolensLayout array) {
  return array == MicrolensLayout::Hexagonal ? "hexagonal" : "square";
}

std::optional<MicrolensLayout> parseMicrolensLayout(const std::string& name) {
  for (MicrolensLayout array : {MicrolensLayout::Square, MicrolensLayout::Hexagonal})
    if (name == microlensLayoutName(array)) return array;
  return std::nullopt;
}

Status validateLfmOptics(const LfmOptics& o) {
  // Each length and ratio finite and positive; NaN fails every comparison, so `!(x > 0)`.
  const std::pair<double, const char*> positives[] = {
      {o.magnification, "magnification"},      {o.numericalAperture, "NA"},
      {o.wavelengthNm, "wavelength"},          {o.tubeFocalLengthMm, "tube lens focal length"},
      {o.microlensPitchUm, "microlens pitch"}, {o.microlensFocalLengthUm, "microlens focal length"},
      {o.pixelSizeUm, "pixel size"},           {o.pixelAspect, "pixel aspect"},
  };
  for (const auto& [value, name] : positives)
    if (!(value > 0) || !std::isfinite(value))
      return usage(std::string(name) + " must be positive, got " + number(value));
  if (!(o.immersionIndex >= 1) || !std::isfinite(o.immersionIndex))
    return usage("immersion index " + number(o.immersionIndex) + " below 1: no medium is less dense than vacuum");
  if (!(o.numericalAperture < o.immersionIndex))
    return usage("NA " + number(o.numericalAperture) + " above the immersion index " + number(o.immersionIndex) +
                 ": no light reaches the objective");
  if (!(o.microlensFillFactor > 0 && o.microlensFillFactor <= 1))
    return usage("microlens fill factor " + number(o.microlensFillFactor) + " outside (0, 1]");
  if (o.supersample < 1 || o.supersample > 64)
    return usage("supersample " + std::to_string(o.supersample) + " outside [1, 64]");
  return {};
}

Result<LfmOptics> parseNapariLfOptics(const std::string& text, const std::string& where, const LfmOptics& defaults) {
  nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) return makeError(ErrorCode::Format, where + ": not JSON");
  if (!json.is_object() || !json.contains("calibrate") || !json["calibrate"].is_object())
    return makeError(ErrorCode::Format, where + ": no \"calibrate\" section");
  const nlohmann::json& section = json["calibrate"];
  LfmOptics optics = defaults;
  const std::pair<const char*, double*> keys[] = {
      {"objective_magnification", &optics.magnification},
      {"objective_na", &optics.numericalAperture},
      {"medium_index", &optics.immersionIndex},
      {"center_wavelength", &optics.wavelengthNm},
      {"tubelens_focal_length", &optics.tubeFocalLengthMm},
      {"ulens_pitch", &optics.microlensPitchUm},
      {"ulens_focal_length", &optics.microlensFocalLengthUm},
      {"ulens_fill_factor", &optics.microlensFillFactor},
      {"pixel_size", &optics.pixelSizeUm},
  };
  for (const auto& [key, out] : keys) {
    if (!section.contains(key)) continue;
    if (!section[key].is_number())
      return makeError(ErrorCode::Format, where + ": calibrate." + key + ": expected a number");
    *out = section[key].get<double>();
  }
  if (section.contains("ulens_array")) {
    const nlohmann::json& value = section["ulens_array"];
    const auto array = value.is_string() ? parseMicrolensLayout(value.get<std::string>()) : std::nullopt;
    if (!array)
      return makeError(ErrorCode::Usage,
                       where + ": calibrate.ulens_array: expected \"square\" or \"hexagonal\", got " + value.dump());
    optics.array = *array;
  }
  if (section.contains("ulens_profile") &&
      !(section["ulens_profile"].is_string() && section["ulens_profile"].get<std::string>() == "rect"))
    return makeError(ErrorCode::Unsupported,
                     where + ": calibrate.ulens_profile: only \"rect\" (apertures filling their cells) is modelled");
  // The sensor at the microlens focal plane is the model's; another distance is not.
  if (section.contains("ulens_focal_distance") && section["ulens_focal_distance"].is_number() &&
      section["ulens_focal_distance"].get<double>() != optics.microlensFocalLengthUm)
    return makeError(ErrorCode::Unsupported,
                     where + ": calibrate.ulens_focal_distance " +
                         number(section["ulens_focal_distance"].get<double>()) +
                         " differs from ulens_focal_length: only a sensor at the microlens focal plane is modelled");
  if (Status valid = validateLfmOptics(optics); !valid)
    return makeError(ErrorCode::Usage, where + ": " + valid.error().message);
  return optics;
}

}  // namespace lfcam
