// What a batch (`lfcam batch`, lfcam.batch in Python) is asked to do, checked before any work: the
// steps applied to every capture, the captures the INPUT arguments stand for (globs expanded,
// folders of inputs listed), and the spec file that may stand for the flags.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/result.hpp"
#include "lfcam/lfm/volume_request.hpp"
#include "lfcam/photo/photo_request.hpp"

namespace lfcam {

// One step and the files it writes under the capture's output folder.
struct BatchStep {
  enum class Kind { Refocus, Stack, Edof, Depth, Page, Photo, Volume } kind;
  std::string text;                // as given, e.g. "refocus:0.5"; recorded in the done-marker
  double slope = 0;                // refocus
  std::vector<double> slopes;      // stack
  std::string name;                // photo: its output is photo_NAME.png
  PhotoRequest photo;              // photo
  LfmVolumeRequest volume;         // volume: its settings, psfPath empty (batchPsfPath gives it)
  std::filesystem::path settings;  // volume: the settings file, as read (relative ones resolved)
  std::vector<std::string> outputs() const;
};

// "refocus:SLOPE", "stack:FROM:TO:N", "edof", "depth", "page", "photo:NAME?FIELD=TEXT&FIELD=TEXT..."
// (any photograph, its fields those of photo_request.hpp, as the viewer's query takes them, e.g.
// photo:tilted?slope=0.5&tilt=1&f-number=2), or "volume:SETTINGS" (a light-field microscope volume,
// SETTINGS napari-LF's metadata.txt or lfcam's optics JSON as lfcam volume --optics takes them, read
// and checked here; a relative path is taken from `base` when given, for a worker whose working
// folder is not the caller's) -> steps; a Usage error naming the bad one, in the request's own words
// for a photograph or settings it refuses.
Result<std::vector<BatchStep>> parseBatchSteps(const std::vector<std::string>& texts,
                                               const std::filesystem::path& base = {});

// A volume step's PSF cache: OUTDIR/psfCacheName(settings), shared by every capture of the batch.
std::filesystem::path batchPsfPath(const BatchStep& step, const std::filesystem::path& outputFolder);

// "refocus:0.5,photo:p?focus-plane=1,2:3,4:5,6,edof" -> its steps: split at every comma but those
// inside a photograph's fields, where only a comma followed by a step's name ends the step (the
// command line's --steps, Python's string).
std::vector<std::string> splitBatchSteps(const std::string& text);

struct BatchCapture {
  std::filesystem::path input;
  std::string name;  // its output folder under OUTDIR: the input's name without extensions
};

// Each INPUT: a light-field file or folder, a raw, a glob (expanded here; matching nothing is a
// Usage error), or a folder of inputs (its entries that are files or light-field folders, the
// `excluded` ones — the white and dark images — left out). Two captures of one name are a Usage error.
Result<std::vector<BatchCapture>> expandBatchInputs(const std::vector<std::string>& inputs,
                                                    const std::vector<std::filesystem::path>& excluded);

// The flags a spec file may stand for; those absent stay empty.
struct BatchSpec {
  std::vector<std::string> inputs, steps;
  std::optional<std::string> output, white, whites, report, dask;
  std::optional<int> jobs;
  std::optional<bool> anyCamera;  // "any_camera"
};
// A JSON object of those keys; an unknown key or wrong type is a Usage error naming the file and the key.
Result<BatchSpec> readBatchSpec(const std::filesystem::path& file);

// A whole batch as given (flags or spec already merged), and as checked and expanded.
struct BatchRequest {
  std::vector<std::string> inputs, steps;
  std::string output, white, whites, report;  // report empty: OUTDIR/batch-report.json
  bool anyCamera = false;
};
// How the captures are decoded: raws of one white image, or raws whose white a white-image database
// (white_database.hpp) chooses capture by capture (of any camera with anyCamera); neither: the
// inputs are light fields.
struct BatchWhite {
  std::filesystem::path image, database;
  bool anyCamera = false;
};
struct BatchPlan {
  std::vector<BatchCapture> captures;
  std::vector<BatchStep> steps;
  std::filesystem::path output, report;
  BatchWhite white;
};
// Usage errors for a missing output, input or step, an unknown step, a white image or database
// that is not a file (or both given), a glob that matches nothing; the white image, the database
// and OUTDIR are never taken as captures.
Result<BatchPlan> planBatch(const BatchRequest& request);

}  // namespace lfcam
