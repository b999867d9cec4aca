// White images of one or more cameras, each calibrated once, and the choice among them for a
// capture: the white of the capture's camera (serial) nearest in zoom step, then among those
// nearest in focus step (LFToolbox's rule, LFSelectFromDatabase).
//
// indexWhites reads calibration data (Lytro MOD_*.RAW + .TXT pairs, loose, in tar archives or in a
// first-generation camera's backup volumes; Lytro white containers; PNG/TIFF whites with a side-car
// naming serial and steps), reads each white's camera setting (raw_image.hpp's CameraSetting, in
// whichever firmware's keys it has), calibrates its grid (calibrate.hpp), and writes the index
// (whites.json, docs/formats.md "White-image database") and, in a folder beside it
// (whites.json -> whites.cache/), each grid and a copy of each white that lay inside an archive.
// Passed over, each with a note naming the file: whites without serial, zoom or focus step, whites
// of another sensor size than most of their camera's, the shorter exposure of two at one setting
// (a first-generation camera stores a dark one beside each), whites whose grid cannot be found.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/raw_io/raw_image.hpp"

namespace lfcam {

struct WhiteRecord {
  std::string name;  // where it came from: "caldata-B5143909630.tar:T1CALIB/MOD_0003.RAW", a path
  CameraSetting setting;
  int width = 0, height = 0;    // sensor pixels
  std::filesystem::path white;  // what a decode reads: the original file, or its copy in the cache
  std::filesystem::path grid;   // its grid.json, in the cache
  double residualPx = 0;        // the grid fit's RMS residual
};

struct WhiteDatabase {
  std::filesystem::path index;      // whites.json
  std::string madeBy;               // the lfcam and calibration that made the grids ("lfcam 0.1.0, calibration 1")
  std::vector<WhiteRecord> whites;  // by serial, zoom step, focus step, name
};

// What made the grids this build reads: a database made by another is refused, as its grids
// could differ from what this lfcam would find.
std::string whiteCalibrationVersion();

// Sources: folders (searched recursively) or files. `note` receives one line per white indexed
// (passedOver false) and per file passed over (true), each naming the file. Format errors name the file (a damaged or
// truncated archive, a file that holds no white, no white left to index); nothing is written then.
Result<WhiteDatabase> indexWhites(const std::vector<std::filesystem::path>& sources, const std::filesystem::path& index,
                                  const ProgressCallback& progress = {},
                                  const std::function<void(const std::string& line, bool passedOver)>& note = {});

// Format error naming the index when it is not one, or when another lfcam made its grids.
Result<WhiteDatabase> readWhiteDatabase(const std::filesystem::path& index);

struct WhiteChoice {
  WhiteRecord white;
  std::string reason;  // one line: which white, why (steps off), and how many were candidates
};

// The white for a capture of `setting` and `width` x `height` pixels, named `capture` in messages.
// Errors name the capture or the index: a capture without zoom or focus step (Format), without a
// serial or of a camera the database does not hold (Usage, unless `anyCamera`: then every camera's
// whites are candidates), no white of the capture's sensor size (Format).
Result<WhiteChoice> chooseWhite(const WhiteDatabase& database, const CameraSetting& setting, int width, int height,
                                bool anyCamera, const std::string& capture);
// The same for a raw, the database read from `index` first.
Result<WhiteChoice> chooseWhite(const std::filesystem::path& index, const RawImage& raw, bool anyCamera,
                                const std::string& capture);

}  // namespace lfcam
