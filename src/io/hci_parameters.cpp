// parameters.cfg of the HCI benchmark (hci_parameters.hpp): a bounded INI reader, the keys lfcam
// uses, and the equivalent plenoptic optics.
#include "io/hci_parameters.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <system_error>

#include "io/io_support.hpp"

namespace lfcam {

namespace {

constexpr std::size_t kMaxBytes = 1 << 20;
constexpr std::size_t kMaxLine = 4096;
constexpr std::size_t kMaxScene = 256;

std::string_view trim(std::string_view text) {
  const auto begin = text.find_first_not_of(" \t\r\f\v");
  if (begin == std::string_view::npos) return {};
  return text.substr(begin, text.find_last_not_of(" \t\r\f\v") - begin + 1);
}

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return out;
}

struct Line {
  int number;
  std::string_view value;
};

// A number within [low, high] (integral when `integral`), else a Format error naming the line.
Result<double> parseNumber(const std::string& name, const std::string& key, const Line& line, double low, double high,
                           bool integral) {
  const std::string_view text = line.value;
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  const std::string where = name + ": line " + std::to_string(line.number) + ": " + key + " = '" +
                            std::string(text.substr(0, 40)) + (text.size() > 40 ? "...'" : "'");
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return makeError(ErrorCode::Format, io::oneLine(where + " is not a number"));
  if (!(value >= low && value <= high) || (integral && value != std::floor(value)))
    return makeError(ErrorCode::Format,
                     io::oneLine(where + " is out of range (" + (integral ? "an integer " : "") + "from " +
                                 std::to_string(low) + " to " + std::to_string(high) + ")"));
  return value;
}

}  // namespace

Result<HciParameters> parseHciParameters(std::string_view text, const std::string& name) {
  if (text.size() > kMaxBytes)
    return makeError(ErrorCode::Format, name + ": " + std::to_string(text.size()) +
                                            " bytes is too large for a parameters.cfg (at most 1 MiB)");
  // key (lower case) -> last line giving it.
  std::vector<std::pair<std::string, Line>> entries;
  int number = 0;
  for (std::size_t position = 0; position < text.size();) {
    std::size_t next = text.find('\n', position);
    if (next == std::string_view::npos) next = text.size();
    const std::string_view raw = text.substr(position, next - position);
    position = next + 1;
    ++number;
    if (raw.size() > kMaxLine)
      return makeError(ErrorCode::Format, name + ": line " + std::to_string(number) + " is longer than " +
                                              std::to_string(kMaxLine) + " characters");
    const std::string_view line = trim(raw);
    if (line.empty() || line[0] == '#' || line[0] == ';' || line[0] == '[') continue;
    const auto separator = line.find_first_of("=:");
    if (separator == std::string_view::npos || separator == 0)
      return makeError(ErrorCode::Format, name + ": line " + std::to_string(number) + ": expected 'key = value'");
    entries.emplace_back(lower(trim(line.substr(0, separator))), Line{number, trim(line.substr(separator + 1))});
  }
  auto find = [&](const std::string& key) -> const Line* {
    for (auto it = entries.rbegin(); it != entries.rend(); ++it)
      if (it->first == key) return &it->second;
    return nullptr;
  };

  HciParameters parameters;
  const double huge = 1e12;
  auto readDouble = [&](const char* key, std::optional<double>& target, double low, double high) -> Status {
    if (const Line* line = find(key)) {
      LFCAM_ASSIGN_OR_RETURN(auto value, parseNumber(name, key, *line, low, high, false));
      target = value;
    }
    return {};
  };
  auto readInt = [&](const char* key, std::optional<int>& target, double high) -> Status {
    if (const Line* line = find(key)) {
      LFCAM_ASSIGN_OR_RETURN(auto value, parseNumber(name, key, *line, 1, high, true));
      target = int(value);
    }
    return {};
  };
  const double tiny = 1e-12;
  LFCAM_TRY(readInt("image_resolution_x_px", parameters.imageWidth, 1 << 20));
  LFCAM_TRY(readInt("image_resolution_y_px", parameters.imageHeight, 1 << 20));
  LFCAM_TRY(readDouble("focal_length_mm", parameters.focalLengthMm, tiny, huge));
  LFCAM_TRY(readDouble("sensor_size_mm", parameters.sensorSizeMm, tiny, huge));
  LFCAM_TRY(readDouble("fstop", parameters.fstop, tiny, huge));
  LFCAM_TRY(readInt("num_cams_x", parameters.camerasX, 100000));
  LFCAM_TRY(readInt("num_cams_y", parameters.camerasY, 100000));
  LFCAM_TRY(readDouble("baseline_mm", parameters.baselineMm, tiny, huge));
  LFCAM_TRY(readDouble("focus_distance_m", parameters.focusDistanceM, tiny, huge));
  LFCAM_TRY(readDouble("disp_min", parameters.disparityMin, -huge, huge));
  LFCAM_TRY(readDouble("disp_max", parameters.disparityMax, -huge, huge));
  if (const Line* line = find("scene")) parameters.scene = io::oneLine(line->value.substr(0, kMaxScene));
  return parameters;
}

Result<HciParameters> readHciParameters(const std::filesystem::path& path) {
  LFCAM_TRY(io::checkReadableFile(path));
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return io::fileError(ErrorCode::Io, path, "cannot read: " + ec.message());
  if (size > kMaxBytes)
    return io::fileError(ErrorCode::Format, path,
                         std::to_string(size) + " bytes is too large for a parameters.cfg (at most 1 MiB)");
  std::ifstream in(path, std::ios::binary);
  if (!in) return io::fileError(ErrorCode::Io, path, "cannot open");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return io::fileError(ErrorCode::Io, path, "read failed");
  return parseHciParameters(text, path.string());
}

std::optional<Optics> hciOptics(const HciParameters& p) {
  if (!p.focalLengthMm || !p.sensorSizeMm || !p.baselineMm || !p.focusDistanceM || (!p.imageWidth && !p.imageHeight))
    return std::nullopt;
  const int pixels = std::max(p.imageWidth.value_or(0), p.imageHeight.value_or(0));
  const double focusMm = *p.focusDistanceM * 1000.0;
  Optics optics;
  optics.lensStepMm = *p.baselineMm;
  optics.spatialStepMm = *p.sensorSizeMm / pixels;
  optics.lensToMicrolensMm = *p.focalLengthMm;
  // The main lens that focuses focus_distance_m onto the film at F (thin lens).
  optics.focalLengthMm = 1.0 / (1.0 / *p.focalLengthMm + 1.0 / focusMm);
  if (!std::isfinite(*optics.focalLengthMm) || !(optics.spatialStepMm > 0)) return std::nullopt;
  return optics;
}

}  // namespace lfcam
