// The light-field PSF as the projectors use it: for each slice and each voxel of a lenslet, the
// sensor pixels its light reaches, largest first until a chosen fraction of its energy (napari-LF
// keeps 95 %), each as a pixel of a period of the array (a lenslet; two rows of lenslets for a
// hexagonal array, LfmOptics::rowsPerPeriod) at an offset from the voxel's own. Most of a
// wave-optics PSF's window is dark: the splats are a few per cent of it (docs/design.md,
// "Microscope volumes").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lfcam/core/progress.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/lfm/psf.hpp"

namespace lfcam {

struct LfmSplat {
  std::uint16_t pixel = 0;     // v N + u: the pixel (u, v) of its period, N x rowsPerPeriod N
  std::int8_t dx = 0, dy = 0;  // that period's offset from the voxel's period
  float weight = 0;            // energy on the pixel from a voxel of unit brightness
};

struct LfmSparsePsf {
  LfmOptics optics;  // frameOptics of the microscope
  PupilModel pupil = PupilModel::AbbeSine;
  LfmGrid grid;
  double keptEnergy = 1;            // of each PSF
  int reach = 0;                    // the largest |dx| or |dy|
  std::vector<std::size_t> begins;  // (depth, j, i) -> its splats [begins[p], begins[p + 1])
  std::vector<LfmSplat> splats;

  int voxelRows() const { return optics.rowsPerPeriod() * grid.voxelsPerLenslet; }  // j in [0, voxelRows())
  std::span<const LfmSplat> of(int depth, int i, int j) const {
    const std::size_t p = (std::size_t(depth) * voxelRows() + j) * grid.voxelsPerLenslet + i;
    return {splats.data() + begins[p], begins[p + 1] - begins[p]};
  }
};

// Each PSF of `set` reduced to its brightest pixels holding `keep` (in (0, 1]) of its energy;
// keep 1 keeps every pixel that is not zero.
LfmSparsePsf sparsePsf(const LfmPsfSet& set, double keep);

// computePsfSet slice by slice, each slice's window fitted to its depth, reduced as it goes: the
// dense set of a deep volume would not fit in memory. progress(fraction) after each slice.
Result<LfmSparsePsf> computeSparsePsf(const LfmOptics& microscope, const LfmGrid& grid, double keep,
                                      PupilModel pupil = PupilModel::AbbeSine, const ProgressCallback& progress = {});

// The PSF cache: an HDF5 file holding the splats and everything they were made for. readPsfCache
// refuses, in one line naming the first difference, a file made for other optics, pupil, grid,
// slices or kept energy (ErrorCode::Usage), or one that is not such a file (ErrorCode::Format).
Status writePsfCache(const LfmSparsePsf& psf, const std::string& path);
Result<LfmSparsePsf> readPsfCache(const std::string& path, const LfmOptics& microscope, const LfmGrid& grid,
                                  double keep, PupilModel pupil = PupilModel::AbbeSine);

}  // namespace lfcam
