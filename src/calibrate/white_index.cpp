// Building a white-image database (white_database.hpp, indexWhites).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <tuple>

#include "calibrate/white_database_json.hpp"
#include "core/atomic_file.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/calibrate/white_database.hpp"
#include "raw_io/lytro_caldata.hpp"

namespace lfcam {

namespace {

namespace fs = std::filesystem;

struct Candidate {
  CaldataWhite white;
  CaldataDescription description;
  const std::string& name() const { return white.pixels.name; }
};

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string stepText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// The cache's name for a white: its place in the index and its own name, in safe characters.
std::string cacheStem(std::size_t place, const CaldataWhite& white) {
  std::string stem =
      fs::path(white.pixels.holder == CaldataFile::Holder::Disk ? white.pixels.file.string() : white.pixels.name)
          .stem()
          .string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  char number[32];
  std::snprintf(number, sizeof number, "%04zu-", place);
  return number + stem;
}

Status writeBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out.flush()) return makeError(ErrorCode::Io, path.string() + ": cannot write");
  return {};
}

// Whites the index cannot use, each passed over with a note: no serial or step, another sensor size
// than most of the camera's, the shorter exposure of two at one setting.
std::vector<Candidate> usable(std::vector<Candidate> candidates,
                              const std::function<void(const std::string&)>& passOver) {
  std::vector<Candidate> kept;
  for (Candidate& c : candidates) {
    const CameraSetting& s = c.description.setting;
    const char* missing = s.serial.empty() ? "camera serial"
                          : !s.zoomStep    ? "zoom step"
                          : !s.focusStep   ? "focus step"
                                           : nullptr;
    if (missing)
      passOver(c.name() + ": its metadata gives no " + missing + ", passed over");
    else
      kept.push_back(std::move(c));
  }
  std::map<std::string, std::map<std::pair<int, int>, int>> sizes;  // serial -> size -> count
  for (const Candidate& c : kept) ++sizes[c.description.setting.serial][{c.description.width, c.description.height}];
  std::map<std::tuple<std::string, double, double>, std::size_t> longest;  // setting -> place in `kept`
  std::vector<Candidate> result;
  for (Candidate& c : kept) {
    const auto& counts = sizes[c.description.setting.serial];
    const auto common = std::max_element(counts.begin(), counts.end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (common->first != std::pair{c.description.width, c.description.height}) {
      passOver(c.name() + ": a white of " + sizeText(c.description.width, c.description.height) +
               " pixels where camera " + c.description.setting.serial + "'s others are " +
               sizeText(common->first.first, common->first.second) + ", passed over");
      continue;
    }
    const CameraSetting& s = c.description.setting;
    const auto key = std::tuple{s.serial, *s.zoomStep, *s.focusStep};
    const auto found = longest.find(key);
    if (found == longest.end()) {
      longest.emplace(key, result.size());
      result.push_back(std::move(c));
      continue;
    }
    Candidate& other = result[found->second];
    const bool longer = s.exposureS.value_or(0) > other.description.setting.exposureS.value_or(0);
    passOver((longer ? other.name() : c.name()) + ": a shorter exposure at the zoom and focus of " +
             (longer ? c.name() : other.name()) + ", passed over");
    if (longer) other = std::move(c);
  }
  std::sort(result.begin(), result.end(), [](const Candidate& a, const Candidate& b) {
    const CameraSetting &x = a.description.setting, &y = b.description.setting;
    return std::tie(x.serial, *x.zoomStep, *x.focusStep, a.name()) <
           std::tie(y.serial, *y.zoomStep, *y.focusStep, b.name());
  });
  return result;
}

}  // namespace

Result<WhiteDatabase> indexWhites(const std::vector<fs::path>& sources, const fs::path& index,
                                  const ProgressCallback& progress,
                                  const std::function<void(const std::string&, bool)>& note) {
  const auto passOver = [&](const std::string& line) {
    if (note) note(line, true);
  };
  fs::path cache = index;
  cache.replace_extension(".cache");
  const fs::path cacheFolder = fs::absolute(cache).lexically_normal();
  std::vector<Candidate> candidates;
  for (const fs::path& source : sources) {
    LFCAM_ASSIGN_OR_RETURN(auto listing, findCaldataWhites(source));
    for (const std::string& warning : listing.warnings) passOver(warning);
    for (CaldataWhite& white : listing.whites) {
      // A folder holding an earlier index: its copies are not whites of their own.
      if (fs::absolute(white.pixels.file).lexically_normal().parent_path() == cacheFolder) continue;
      LFCAM_ASSIGN_OR_RETURN(auto description, describeCaldataWhite(white));
      candidates.push_back({std::move(white), std::move(description)});
    }
  }
  const std::vector<Candidate> whites = usable(std::move(candidates), passOver);
  if (whites.empty())
    return makeError(ErrorCode::Format, index.string() + ": no white left to index (the notes above say why)");

  // Each white calibrated once; its grid, and a copy of a white inside an archive, in the cache.
  WhiteDatabase database{.index = index, .madeBy = whiteCalibrationVersion()};
  LFCAM_TRY(writeFolderAtomically(cache, [&](const fs::path& folder) -> Status {
    for (std::size_t k = 0; k < whites.size(); ++k) {
      const Candidate& c = whites[k];
      LFCAM_ASSIGN_OR_RETURN(auto raw, readCaldataWhite(c.white));
      auto grid = calibrateGrid(raw, CalibrationOptions{}, c.name());
      if (!grid) {
        passOver(grid.error().message + ", passed over");
        continue;
      }
      const std::string stem = cacheStem(k, c.white);
      WhiteRecord record{.name = c.name(),
                         .setting = c.description.setting,
                         .width = raw.mosaic.width(),
                         .height = raw.mosaic.height(),
                         .white = c.white.pixels.file,
                         .grid = cache / (stem + ".grid.json"),
                         .residualPx = grid->fit.rmsResidualPx};
      LFCAM_TRY(writeGrid(folder / (stem + ".grid.json"), *grid));
      if (c.white.pixels.holder != CaldataFile::Holder::Disk) {
        record.white = cache / (stem + ".RAW");
        for (const auto& [file, extension] :
             {std::pair{&c.white.pixels, ".RAW"}, std::pair{&c.white.description, ".TXT"}}) {
          LFCAM_ASSIGN_OR_RETURN(auto bytes, readCaldataFile(*file));
          LFCAM_TRY(writeBytes(folder / (stem + extension), bytes));
        }
      }
      const CameraSetting& s = record.setting;
      if (note)
        note(record.name + ": camera " + s.serial + (s.model.empty() ? "" : " (" + s.model + ")") + ", zoom step " +
                 stepText(*s.zoomStep) + ", focus step " + stepText(*s.focusStep) + ", " +
                 sizeText(record.width, record.height) + ", grid pitch " + stepText(grid->pitchX) + " px, residual " +
                 stepText(record.residualPx) + " px RMS",
             false);
      database.whites.push_back(std::move(record));
      if (progress) progress(double(k + 1) / double(whites.size()));
    }
    if (database.whites.empty())
      return makeError(ErrorCode::Format, index.string() + ": no white could be calibrated (the notes above say why)");
    return {};
  }));
  LFCAM_TRY(writeWhiteDatabase(database));
  return database;
}

}  // namespace lfcam
