#include "lfcam/lfm/volume_request.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include "core/memory_budget.hpp"
#include "io/hdf5_support.hpp"
#include "lfcam/lfm/napari_lf_calibration.hpp"
#include "lfcam/lfm/sparse_psf.hpp"

#include "lfm/message_text.hpp"

namespace lfcam {

using lfm::number;
using lfm::usage;

std::vector<double> LfmVolumeRequest::depthsUm() const {
  std::vector<double> depths;
  for (int i = 0; i < slices; ++i) depths.push_back(zCenterUm + (i - 0.5 * (slices - 1)) * umPerSlice);
  return depths;
}

Result<LfmVolumeRequest> parseLfmSettings(const std::string& text, const std::string& where,
                                          const LfmVolumeRequest& defaults) {
  nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded() || !json.is_object()) return makeError(ErrorCode::Format, where + ": not a JSON object");
  // lfcam's own file: napari-LF's calibrate keys at the top level.
  if (!json.contains("calibrate")) json = nlohmann::json{{"calibrate", json}};
  LfmVolumeRequest request = defaults;
  LFCAM_ASSIGN_OR_RETURN(request.optics, parseNapariLfOptics(json.dump(), where, defaults.optics));
  const nlohmann::json& calibrate = json["calibrate"];
  const nlohmann::json deconvolve = json.contains("deconvolve") ? json["deconvolve"] : nlohmann::json::object();
  auto read = [&](const nlohmann::json& section, const char* sectionName, const char* key, auto& out) -> Status {
    if (!section.is_object() || !section.contains(key)) return {};
    const nlohmann::json& value = section[key];
    using T = std::decay_t<decltype(out)>;
    if constexpr (std::is_same_v<T, int>) {
      if (!value.is_number_integer())
        return makeError(ErrorCode::Format, where + ": " + sectionName + "." + key + ": expected an integer");
      out = value.get<int>();
    } else {
      if (!value.is_number())
        return makeError(ErrorCode::Format, where + ": " + sectionName + "." + key + ": expected a number");
      out = value.get<double>();
    }
    return {};
  };
  LFCAM_TRY(read(calibrate, "calibrate", "num_slices", request.slices));
  LFCAM_TRY(read(calibrate, "calibrate", "um_per_slice", request.umPerSlice));
  LFCAM_TRY(read(calibrate, "calibrate", "z_center", request.zCenterUm));
  LFCAM_TRY(read(calibrate, "calibrate", "supersample", request.supersample));
  LFCAM_TRY(read(deconvolve, "deconvolve", "max_iter", request.reconstruct.iterations));
  LFCAM_TRY(read(deconvolve, "deconvolve", "conv_thresh", request.reconstruct.tolerance));
  return request;
}

std::string psfCacheName(const LfmVolumeRequest& r) {
  std::ostringstream key;
  key.precision(17);
  const LfmOptics& o = r.optics;
  key << o.magnification << ' ' << o.numericalAperture << ' ' << o.immersionIndex << ' ' << o.wavelengthNm << ' '
      << o.tubeFocalLengthMm << ' ' << o.microlensPitchUm << ' ' << o.microlensFocalLengthUm << ' '
      << o.microlensFillFactor << ' ' << int(o.array) << ' ' << o.pixelSizeUm << ' ' << o.supersample << ' ' << r.slices
      << ' ' << r.umPerSlice << ' ' << r.zCenterUm << ' ' << r.supersample << ' ' << r.psfEnergy;
  char name[64];
  std::snprintf(name, sizeof name, "lfcam-psf-%016zx.h5", std::hash<std::string>{}(key.str()));
  return name;
}

Status checkVolumeRequest(const LfmVolumeRequest& request) {
  LFCAM_TRY(validateLfmOptics(request.optics));
  if (request.slices < 1 || request.slices > 1000)
    return usage("slices " + std::to_string(request.slices) + " outside [1, 1000]");
  if (!(request.umPerSlice > 0) || !std::isfinite(request.umPerSlice))
    return usage("um per slice " + number(request.umPerSlice) + " must be positive");
  if (!std::isfinite(request.zCenterUm)) return usage("z centre must be finite");
  if (request.supersample < 1 || request.supersample > 255)
    return usage("supersample " + std::to_string(request.supersample) + " outside [1, 255]");
  if (!(request.psfEnergy > 0 && request.psfEnergy <= 1))
    return usage("PSF energy " + number(request.psfEnergy) + " outside (0, 1]");
  if (request.reconstruct.iterations < 1 || request.reconstruct.iterations > 10000)
    return usage("iterations " + std::to_string(request.reconstruct.iterations) + " outside [1, 10000]");
  return {};
}

namespace {

// The frame's pixels a lenslet N, checked against the request: square, near the optics' period,
// the supersample within it.
Result<int> checkFrame(const LightFieldShape& shape, const LfmVolumeRequest& request, const std::string& where) {
  const int n = shape.nu;
  const double period = request.optics.microlensPitchUm / request.optics.pixelSizeUm;
  if (shape.nu != shape.nv || n < 2)
    return usage(where + ": " + std::to_string(shape.nu) + " x " + std::to_string(shape.nv) +
                 " pixels a lenslet: a microscope frame needs a square count (rectify it to one)");
  if (std::abs(n - period) > 0.25 * period)
    return usage(where + ": " + std::to_string(n) + " pixels a lenslet, but the optics give " + number(period) +
                 " (pitch " + number(request.optics.microlensPitchUm) + " um / pixel " +
                 number(request.optics.pixelSizeUm) + " um): check the pitch, the pixel size or the frame");
  if (request.supersample > n)
    return usage(where + ": supersample " + std::to_string(request.supersample) + " above the " + std::to_string(n) +
                 " pixels a lenslet");
  if (shape.nt < request.optics.rowsPerPeriod())
    return usage(where + ": one row of lenslets: a hexagonal array's frame needs two");
  return n;
}

// The lenslet rows the volume covers: a hexagonal array repeats every two rows (LfmProjector),
// so an odd last row is left out.
int lensletRowsUsed(const LightFieldShape& shape, const LfmOptics& optics) {
  return shape.nt - shape.nt % optics.rowsPerPeriod();
}

LfmGrid gridOf(const LfmVolumeRequest& request, int pixelsPerLenslet) {
  return {
      .pixelsPerLenslet = pixelsPerLenslet, .voxelsPerLenslet = request.supersample, .depthsUm = request.depthsUm()};
}

bool psfCached(const LfmVolumeRequest& request) {
  return !request.psfPath.empty() && std::filesystem::exists(request.psfPath);
}

// The PSF of the grid: read from request.psfPath when it exists (refused when of other settings),
// else computed and written there when set.
Result<LfmSparsePsf> volumePsf(const LfmVolumeRequest& request, const LfmGrid& grid, const std::string& where,
                               const ProgressCallback& progress) {
  if (psfCached(request)) return readPsfCache(request.psfPath, request.optics, grid, request.psfEnergy);
  auto psf = computeSparsePsf(request.optics, grid, request.psfEnergy, PupilModel::AbbeSine, [&](double f) {
    if (progress) progress(f);
  });
  if (!psf) return makeError(psf.error().code, where + ": " + psf.error().message);
  if (!request.psfPath.empty()) LFCAM_TRY(writePsfCache(psf.value(), request.psfPath));
  return psf;
}

Status parseObjective(const std::string& text, LfmOptics& optics) {
  const Error bad =
      makeError(ErrorCode::Usage, "--objective: expected MAGx/NA/MEDIUM as 60x/1.2/water, got '" + text + "'");
  std::istringstream in(text);
  std::string magnification, na, medium;
  if (!std::getline(in, magnification, '/') || !std::getline(in, na, '/') || !std::getline(in, medium) ||
      magnification.empty() || (magnification.back() != 'x' && magnification.back() != 'X'))
    return bad;
  try {
    std::size_t used = 0;
    optics.magnification = std::stod(magnification.substr(0, magnification.size() - 1), &used);
    if (used != magnification.size() - 1) return bad;
    optics.numericalAperture = std::stod(na, &used);
    if (used != na.size()) return bad;
    if (medium == "water")
      optics.immersionIndex = 1.333;
    else if (medium == "oil")
      optics.immersionIndex = 1.515;
    else if (medium == "glycerol")
      optics.immersionIndex = 1.47;
    else if (medium == "air")
      optics.immersionIndex = 1.0;
    else {
      optics.immersionIndex = std::stod(medium, &used);
      if (used != medium.size()) return bad;
    }
  } catch (const std::exception&) {
    return bad;
  }
  return {};
}

}  // namespace

Status cacheVolumePsf(const LightField& frame, const LfmVolumeRequest& request, const std::string& where,
                      const ProgressCallback& progress) {
  if (request.psfPath.empty() || psfCached(request)) return {};
  LFCAM_TRY(checkVolumeRequest(request));
  LFCAM_ASSIGN_OR_RETURN(const int n, checkFrame(frame.shape(), request, where));
  const Result<LfmSparsePsf> psf = volumePsf(request, gridOf(request, n), where, progress);
  if (!psf) return psf.error();
  return {};
}

Result<LfmVolumeResult> reconstructVolume(const LightField& frame, const LfmVolumeRequest& request,
                                          const std::string& where, const ProgressCallback& progress) {
  auto fail = [&](const Error& error) { return makeError(error.code, where + ": " + error.message); };
  if (Status checked = checkVolumeRequest(request); !checked) return checked.error();
  const LightFieldShape shape = frame.shape();
  LFCAM_ASSIGN_OR_RETURN(const int n, checkFrame(shape, request, where));
  const int rows = lensletRowsUsed(shape, request.optics);
  // The solver holds about six volumes (the estimate, its correction, the sensitivity and the
  // padded planes of both projections) and a few frames.
  const auto voxels = checkedProduct({std::uint64_t(shape.ns) * request.supersample,
                                      std::uint64_t(rows) * request.supersample, std::uint64_t(request.slices)});
  LFCAM_TRY(checkMemory(where, voxels ? checkedProduct({*voxels, 4 * 6}) : std::nullopt,
                        "the volume (" + std::to_string(request.slices) + " slices)"));

  LfmVolumeResult result;
  result.psfFromCache = psfCached(request);
  const double psfShare = result.psfFromCache ? 0 : 0.5;
  LFCAM_ASSIGN_OR_RETURN(const auto psf, volumePsf(request, gridOf(request, n), where, [&](double f) {
                           if (progress) progress(psfShare * f);
                         }));
  result.psfSplats = psf.splats.size();

  // A frame decoded with a white image holds radiance (the raw over the white) and the white as
  // its weight: the light collected is their product, and the white over the model's frame of a
  // uniform volume is the radiometry R of the model y = R (H x).
  Image image(shape.ns * n, rows * n, 1), white(shape.ns * n, rows * n, 1);
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u)
      for (int t = 0; t < rows; ++t)
        for (int s = 0; s < shape.ns; ++s) {
          double sum = 0;
          for (int c = 0; c < shape.channels; ++c) sum += frame.at(u, v, s, t, c);
          const float weight = frame.hasWeight() ? frame.weightPlane(u, v)[std::size_t(t) * shape.ns + s] : 1.0f;
          image.at(s * n + u, t * n + v, 0) = float(sum / shape.channels) * weight;
          white.at(s * n + u, t * n + v, 0) = weight;
        }
  const LfmProjector projector(psf, shape.ns, rows);
  std::optional<Image> radiometry;
  if (frame.hasWeight()) {
    Volume uniform = projector.emptyVolume();
    std::fill(uniform.voxels().begin(), uniform.voxels().end(), 1.0f);
    radiometry = projector.forward(uniform);
    const float peak = *std::max_element(radiometry->pixels().begin(), radiometry->pixels().end());
    for (std::size_t i = 0; i < radiometry->pixels().size(); ++i) {
      float& r = radiometry->pixels()[i];
      r = r > 1e-3f * peak ? white.pixels()[i] / r : 0.0f;
    }
  }
  auto reconstruction = reconstructVolume(
      projector, image, request.reconstruct,
      [&](double f) {
        if (progress) progress(psfShare + (1 - psfShare) * f);
      },
      radiometry ? &*radiometry : nullptr);
  if (!reconstruction) return fail(reconstruction.error());
  result.reconstruction = std::move(reconstruction.value());
  return result;
}

Result<LfmVolumeRequest> volumeRequestFrom(const LfmVolumeSettings& given) {
  LfmVolumeRequest request;
  if (!given.opticsFile.empty()) {
    std::ostringstream text;
    if (io::startsLikeHdf5(given.opticsFile)) {
      LFCAM_ASSIGN_OR_RETURN(const std::string settings, napariLfCalibrationSettings(given.opticsFile));
      text << settings;
    } else {
      std::ifstream file(given.opticsFile, std::ios::binary);
      if (!file) return makeError(ErrorCode::Io, given.opticsFile + ": cannot open");
      text << file.rdbuf();
    }
    LFCAM_ASSIGN_OR_RETURN(request, parseLfmSettings(text.str(), given.opticsFile, request));
  }
  if (!given.objective.empty()) LFCAM_TRY(parseObjective(given.objective, request.optics));
  auto set = [](const auto& value, auto& field) {
    if (value) field = *value;
  };
  set(given.wavelengthNm, request.optics.wavelengthNm);
  set(given.tubeLensMm, request.optics.tubeFocalLengthMm);
  set(given.pitchUm, request.optics.microlensPitchUm);
  set(given.microlensFocalLengthUm, request.optics.microlensFocalLengthUm);
  set(given.pixelSizeUm, request.optics.pixelSizeUm);
  if (!given.microlensArray.empty()) {
    const auto array = parseMicrolensLayout(given.microlensArray);
    if (!array) return usage("--microlens-array: expected square or hexagonal, got '" + given.microlensArray + "'");
    request.optics.array = *array;
  }
  set(given.slices, request.slices);
  set(given.umPerSlice, request.umPerSlice);
  set(given.zCenterUm, request.zCenterUm);
  set(given.supersample, request.supersample);
  set(given.iterations, request.reconstruct.iterations);
  set(given.tolerance, request.reconstruct.tolerance);
  set(given.background, request.reconstruct.background);
  set(given.tvWeight, request.reconstruct.tvWeight);
  set(given.psfEnergy, request.psfEnergy);
  if (given.solver == "backprojection")
    request.reconstruct.solver = LfmSolver::BackProjection;
  else if (given.solver != "rl")
    return usage("--solver: expected rl or backprojection, got '" + given.solver + "'");
  if (given.opticsFile.empty() && given.objective.empty())
    return usage("--optics or --objective: the microscope is needed");
  if (!given.slices && request.slices == 0) return usage("--slices: how many z-slices (or num_slices in --optics)");
  if (Status checked = checkVolumeRequest(request); !checked) return usage(checked.error().message);
  return request;
}

}  // namespace lfcam
