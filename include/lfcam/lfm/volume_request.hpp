// One light-field microscope reconstruction as every front end asks for it (lfcam volume, the
// Python package, batch steps): the microscope, the volume's slices and sampling, the PSF cache
// and the solver, then a volume from a decoded frame.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "lfcam/core/light_field.hpp"
#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/lfm/optics.hpp"
#include "lfcam/lfm/reconstruct.hpp"

namespace lfcam {

struct LfmVolumeRequest {
  LfmOptics optics;
  int slices = 0;           // >= 1
  double umPerSlice = 1;    // > 0, the slices' spacing in the specimen
  double zCenterUm = 0;     // depth of the middle of the slices (napari-LF's z_center)
  int supersample = 1;      // voxels across a lenslet (napari-LF's supersample), in [1, N]
  double psfEnergy = 0.95;  // of each PSF the projectors keep (napari-LF keeps 95 %)
  // The PSF cache: read when it holds these settings, refused when it holds others; computed and
  // written there when absent. Empty: computed, not kept.
  std::string psfPath;
  LfmReconstructOptions reconstruct;

  // napari-LF's slices: zCenter + (i - (slices - 1) / 2) umPerSlice, i = 0 nearest... as it lists them.
  std::vector<double> depthsUm() const;
};

// The settings of `text`, over `defaults`: napari-LF's metadata.txt (its "calibrate" section's
// optics, num_slices, um_per_slice, z_center and supersample; its "deconvolve" section's
// max_iter and conv_thresh; not its background_level, in the raw's counts where lfcam's frames hold
// [0, 1]), or lfcam's optics JSON (the same keys, at the top
// level). `where` names the file in messages.
Result<LfmVolumeRequest> parseLfmSettings(const std::string& text, const std::string& where,
                                          const LfmVolumeRequest& defaults = {});

// What a front end was given (the command line's flags, Python's keywords): a settings file and the
// values that override it. Empty strings and absent values leave the file's (or the default).
struct LfmVolumeSettings {
  // napari-LF's metadata.txt or .lfc calibration (napari_lf_calibration.hpp), or lfcam's optics
  // JSON (parseLfmSettings)
  std::string opticsFile;
  std::string objective;       // "MAGx/NA/MEDIUM" as "60x/1.2/water" (water, oil, glycerol, air, an index)
  std::string solver = "rl";   // "rl" or "backprojection"
  std::string microlensArray;  // "square" or "hexagonal"
  std::optional<double> wavelengthNm, tubeLensMm, pitchUm, microlensFocalLengthUm, pixelSizeUm, umPerSlice, zCenterUm,
      background, tolerance, tvWeight, psfEnergy;
  std::optional<int> slices, supersample, iterations;
};

// The request they make: the file, then the objective, then each value; one line, in the command
// line's words, for an unreadable file, a bad objective or solver, no microscope (neither file nor
// objective), no slice count, and checkVolumeRequest's refusals. psfPath is left to the caller.
Result<LfmVolumeRequest> volumeRequestFrom(const LfmVolumeSettings& settings);

// The PSF cache's file name for these settings, "lfcam-psf-<hash of the settings>.h5": the default
// cache beside a frame (lfcam volume) or in a batch's output folder, so that a time series shares
// one and other settings get their own.
std::string psfCacheName(const LfmVolumeRequest& request);

// What can be checked before the frame is read: the optics, slices, sampling, energy, solver.
Status checkVolumeRequest(const LfmVolumeRequest& request);

struct LfmVolumeResult {
  LfmReconstruction reconstruction;
  bool psfFromCache = false;
  std::size_t psfSplats = 0;
};

// The volume of a decoded frame: a light field of N x N views (colour averaged to grey),
// its N within a quarter of the optics' pitch / pixel size. For a hexagonal array, lenslet (s, t)'s
// N x N pixels tile its brick, a pitch wide and a row of lenslets (sqrt(3)/2 pitch) high, odd rows t
// half a pitch toward +s (psf.hpp's LfmGrid); an odd last row is left out. `where` (the frame's
// file) prefixes every message. progress: the PSF's computation (when not cached) and the iterations.
Result<LfmVolumeResult> reconstructVolume(const LightField& frame, const LfmVolumeRequest& request,
                                          const std::string& where, const ProgressCallback& progress = {});

// The PSF cache at request.psfPath for this frame's lenslets (checked as reconstructVolume checks
// them), computed and written when absent; nothing when it exists or no path is set. A batch calls
// it once before its captures, so that each only reads the cache.
Status cacheVolumePsf(const LightField& frame, const LfmVolumeRequest& request, const std::string& where,
                      const ProgressCallback& progress = {});

}  // namespace lfcam
