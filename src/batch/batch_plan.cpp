#include "lfcam/batch/batch_plan.hpp"

#include <glob.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lfcam/focused/focused_capture.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/focal_stack.hpp"
#include "photo/focal_stack_output.hpp"

namespace lfcam {
namespace fs = std::filesystem;

namespace {

constexpr std::array<const char*, 7> kStepNames{"refocus", "stack", "edof", "depth", "page", "photo", "volume"};

// "volume:SETTINGS": the settings read and checked as lfcam volume --optics reads them, so that a bad
// file is refused before any capture runs.
Result<BatchStep> parseVolumeStep(const std::string& text, const std::string& argument, const fs::path& base) {
  const auto refuse = [&](const std::string& message) {
    return makeError(ErrorCode::Usage, "--steps: '" + text + "': " + message);
  };
  if (argument.empty()) return refuse("expected volume:SETTINGS (napari-LF's metadata.txt or an optics JSON)");
  BatchStep step{.kind = BatchStep::Kind::Volume, .text = text, .settings = base / argument};
  std::ifstream in(step.settings, std::ios::binary);
  if (!in) return refuse("cannot read " + step.settings.string());
  std::ostringstream contents;
  contents << in.rdbuf();
  auto request = parseLfmSettings(contents.str(), step.settings.string());
  if (!request) return refuse(request.error().message);
  if (request->slices == 0) return refuse(step.settings.string() + ": num_slices missing");
  if (Status checked = checkVolumeRequest(*request); !checked) return refuse(checked.error().message);
  step.volume = std::move(*request);
  return step;
}

Result<BatchStep> parseBatchStep(const std::string& text, const fs::path& base) {
  const std::string name = text.substr(0, text.find(':'));
  const std::string argument = text.find(':') == std::string::npos ? "" : text.substr(text.find(':') + 1);
  const auto usage = [&](const std::string& form) {
    return makeError(ErrorCode::Usage, "--steps: '" + text + "': expected " + form);
  };
  if (name == "refocus") {
    double slope = 0;
    char end = 0;
    if (std::sscanf(argument.c_str(), "%lf%c", &slope, &end) != 1 || !std::isfinite(slope))
      return usage("refocus:SLOPE");
    return BatchStep{.kind = BatchStep::Kind::Refocus, .text = text, .slope = slope};
  }
  if (name == "photo") {
    const std::string form = "photo:NAME?FIELD=TEXT&... (NAME of letters, digits, - and _)";
    const auto question = argument.find('?');
    BatchStep step{.kind = BatchStep::Kind::Photo, .text = text, .name = argument.substr(0, question)};
    if (step.name.empty() || question == std::string::npos ||
        step.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_") !=
            std::string::npos)
      return usage(form);
    std::string fields = argument.substr(question + 1);
    for (std::size_t start = 0; start <= fields.size();) {
      const std::size_t end = std::min(fields.find('&', start), fields.size());
      const std::string field = fields.substr(start, end - start);
      const auto equals = field.find('=');
      if (equals == std::string::npos) return usage(form);
      if (Status set = setPhotoField(step.photo, field.substr(0, equals), field.substr(equals + 1)); !set)
        return makeError(set.error().code, "--steps: '" + text + "': " + set.error().message);
      start = end + 1;
    }
    if (Status checked = checkPhotoRequest(step.photo); !checked)
      return makeError(ErrorCode::Usage, "--steps: '" + text + "': " + checked.error().message);
    return step;
  }
  if (name == "volume") return parseVolumeStep(text, argument, base);
  if (name == "stack") {
    auto slopes = parseEvenlySpaced(argument, "--steps stack");
    if (!slopes) return usage("stack:FROM:TO:N (N 1 to 100000)");
    return BatchStep{.kind = BatchStep::Kind::Stack, .text = text, .slopes = *slopes};
  }
  const std::map<std::string, BatchStep::Kind> plain{
      {"edof", BatchStep::Kind::Edof}, {"depth", BatchStep::Kind::Depth}, {"page", BatchStep::Kind::Page}};
  const auto found = plain.find(name);
  if (found == plain.end())
    return makeError(ErrorCode::Usage,
                     "--steps: unknown step '" + text +
                         "' (refocus:SLOPE, stack:FROM:TO:N, edof, depth, page, photo:NAME?FIELD=TEXT&..., "
                         "volume:SETTINGS)");
  if (!argument.empty() || text.find(':') != std::string::npos) return usage(name + " without an argument");
  return BatchStep{.kind = found->second, .text = text};
}

// "IMG_0001.lf.h5" -> "IMG_0001"; a folder keeps its name.
std::string captureName(const fs::path& input) {
  std::string name = input.filename().string();
  if (name.empty()) name = input.parent_path().filename().string();  // "folder/"
  if (fs::is_directory(input)) return name;
  return name.substr(0, std::max<std::size_t>(1, name.find('.')));
}

bool isGlob(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

Result<std::vector<fs::path>> expandGlob(const std::string& pattern) {
  glob_t matches{};
  const int status = ::glob(pattern.c_str(), 0, nullptr, &matches);
  std::vector<fs::path> paths(matches.gl_pathv, matches.gl_pathv + matches.gl_pathc);
  ::globfree(&matches);
  if (status == GLOB_NOMATCH || paths.empty())
    return makeError(ErrorCode::Usage, pattern + ": no file matches this pattern");
  if (status != 0) return makeError(ErrorCode::Io, pattern + ": cannot list the files it matches");
  return paths;
}

}  // namespace

std::vector<std::string> BatchStep::outputs() const {
  switch (kind) {
    case Kind::Refocus: return {"refocus_" + text.substr(text.find(':') + 1) + ".png"};
    case Kind::Stack: {
      std::vector<std::string> files{"stack/stack.json"};
      for (std::size_t k = 0; k < slopes.size(); ++k) files.push_back("stack/" + stackSliceName(int(k), "png"));
      return files;
    }
    case Kind::Edof: return {"all-in-focus.png"};
    case Kind::Depth: return {"depth.pfm", "depth.png"};
    case Kind::Page: return {"page.html"};
    case Kind::Photo: return {"photo_" + name + ".png"};
    case Kind::Volume: return {"volume.tif"};
  }
  return {};
}

fs::path batchPsfPath(const BatchStep& step, const fs::path& outputFolder) {
  return outputFolder / psfCacheName(step.volume);
}

std::vector<std::string> splitBatchSteps(const std::string& text) {
  std::vector<std::string> steps;
  std::size_t start = 0;
  for (std::size_t comma = text.find(','); comma != std::string::npos; comma = text.find(',', comma + 1)) {
    // Inside a photograph's fields, only a comma that a step's name follows ends it.
    const std::string next = text.substr(comma + 1);
    const bool startsAStep = std::any_of(kStepNames.begin(), kStepNames.end(), [&](const char* name) {
      const std::size_t length = std::strlen(name);
      return next.compare(0, length, name) == 0 &&
             (next.size() == length || next[length] == ':' || next[length] == ',');
    });
    if (text.compare(start, 6, "photo:") == 0 && !startsAStep) continue;
    steps.push_back(text.substr(start, comma - start));
    start = comma + 1;
  }
  steps.push_back(text.substr(start));
  return steps;
}

Result<std::vector<BatchStep>> parseBatchSteps(const std::vector<std::string>& texts, const fs::path& base) {
  std::vector<BatchStep> steps;
  for (const std::string& text : texts) {
    LFCAM_ASSIGN_OR_RETURN(auto step, parseBatchStep(text, base));
    steps.push_back(std::move(step));
  }
  if (steps.empty()) return makeError(ErrorCode::Usage, "--steps: give at least one step");
  return steps;
}

Result<std::vector<BatchCapture>> expandBatchInputs(const std::vector<std::string>& inputs,
                                                    const std::vector<fs::path>& excluded) {
  std::vector<fs::path> paths;
  for (const std::string& input : inputs) {
    if (isGlob(input) && !fs::exists(input)) {
      LFCAM_ASSIGN_OR_RETURN(auto matches, expandGlob(input));
      paths.insert(paths.end(), matches.begin(), matches.end());
    } else if (!fs::exists(input)) {
      return makeError(ErrorCode::Usage, input + ": no such file or folder");
    } else if (fs::is_directory(input) && !detectLightFieldFormat(input)) {
      std::vector<fs::path> entries;
      for (const auto& entry : fs::directory_iterator(input)) {
        const bool hidden = entry.path().filename().string().front() == '.';
        const bool lightFieldFolder = entry.is_directory() && detectLightFieldFormat(entry.path());
        if (!hidden && (entry.is_regular_file() || lightFieldFolder)) entries.push_back(entry.path());
      }
      // A focused capture's calibration beside it (NAME.xml) is part of it, not an input.
      std::vector<fs::path> calibrations;
      for (const fs::path& entry : entries)
        if (const auto calibration = focusedCalibrationBeside(entry); calibration && *calibration != entry)
          calibrations.push_back(*calibration);
      std::erase_if(entries, [&](const fs::path& entry) {
        return std::find(calibrations.begin(), calibrations.end(), entry) != calibrations.end();
      });
      std::sort(entries.begin(), entries.end());
      paths.insert(paths.end(), entries.begin(), entries.end());
    } else {
      paths.emplace_back(input);
    }
  }
  std::vector<BatchCapture> captures;
  std::map<std::string, fs::path> byName;
  for (const fs::path& path : paths) {
    std::error_code ec;
    const bool isExcluded = std::any_of(excluded.begin(), excluded.end(),
                                        [&](const fs::path& other) { return fs::equivalent(path, other, ec); });
    if (isExcluded) continue;
    const std::string name = captureName(path);
    const auto [previous, added] = byName.emplace(name, path);
    if (!added)
      return makeError(ErrorCode::Usage, path.string() + ": same output folder '" + name + "' as " +
                                             previous->second.string() + "; rename one");
    captures.push_back({path, name});
  }
  if (captures.empty()) return makeError(ErrorCode::Usage, "batch: no input");
  return captures;
}

Result<BatchSpec> readBatchSpec(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return makeError(ErrorCode::Usage, file.string() + ": cannot read the spec file");
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded() || !json.is_object())
    return makeError(ErrorCode::Usage, file.string() + ": not a JSON object");
  BatchSpec spec;
  for (const auto& entry : json.items()) {
    // Named references, not a structured binding: clang 14 cannot capture bindings in lambdas.
    const std::string& key = entry.key();
    const nlohmann::json& value = entry.value();
    const auto wrongType = [&, name = key](const char* expected) {
      return makeError(ErrorCode::Usage, file.string() + ": '" + name + "' must be " + expected);
    };
    const auto strings = [&](std::vector<std::string>& into) -> Status {
      if (value.is_string()) {
        into.push_back(value.get<std::string>());
        return {};
      }
      if (!value.is_array()) return wrongType("a string or an array of strings");
      for (const auto& item : value) {
        if (!item.is_string()) return wrongType("a string or an array of strings");
        into.push_back(item.get<std::string>());
      }
      return {};
    };
    if (key == "inputs") {
      LFCAM_TRY(strings(spec.inputs));
    } else if (key == "steps") {
      LFCAM_TRY(strings(spec.steps));
    } else if (key == "output" || key == "white" || key == "whites" || key == "report" || key == "dask") {
      if (!value.is_string()) return wrongType("a string");
      (key == "output"   ? spec.output
       : key == "white"  ? spec.white
       : key == "whites" ? spec.whites
       : key == "dask"   ? spec.dask
                         : spec.report) = value.get<std::string>();
    } else if (key == "any_camera") {
      if (!value.is_boolean()) return wrongType("true or false");
      spec.anyCamera = value.get<bool>();
    } else if (key == "jobs") {
      if (!value.is_number_integer() || value.get<int>() < 1) return wrongType("a whole number from 1");
      spec.jobs = value.get<int>();
    } else {
      return makeError(ErrorCode::Usage,
                       file.string() + ": unknown key '" + key +
                           "' (inputs, steps, output, white, whites, any_camera, jobs, dask, report)");
    }
  }
  return spec;
}

Result<BatchPlan> planBatch(const BatchRequest& request) {
  if (request.output.empty()) return makeError(ErrorCode::Usage, "batch: give the output folder with -o");
  if (request.inputs.empty()) return makeError(ErrorCode::Usage, "batch: give at least one INPUT");
  BatchPlan plan{.output = request.output,
                 .white = {.image = request.white, .database = request.whites, .anyCamera = request.anyCamera}};
  LFCAM_ASSIGN_OR_RETURN(plan.steps, parseBatchSteps(request.steps));
  if (!request.white.empty() && !request.whites.empty())
    return makeError(ErrorCode::Usage, request.whites + ": give --white or --whites, not both");
  std::vector<fs::path> excluded{plan.output};
  for (const auto& [file, flag] : {std::pair{&request.white, "--white"}, std::pair{&request.whites, "--whites"}}) {
    if (file->empty()) continue;
    if (!fs::is_regular_file(*file)) return makeError(ErrorCode::Usage, *file + ": " + flag + ": no such file");
    excluded.emplace_back(*file);
  }
  LFCAM_ASSIGN_OR_RETURN(plan.captures, expandBatchInputs(request.inputs, excluded));
  plan.report = request.report.empty() ? plan.output / "batch-report.json" : fs::path(request.report);
  return plan;
}

}  // namespace lfcam
