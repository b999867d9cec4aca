#include "lfcam/lfm/sparse_psf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "core/parallel.hpp"
#include "lfm/message_text.hpp"

namespace lfcam {

namespace {

// Floor division: a window row above the centre lies in an earlier period.
int floorDivide(int a, int d) { return a >= 0 ? a / d : -((-a + d - 1) / d); }

// The splats of one dense PSF: its pixels by falling energy until `keep` of the total.
std::vector<LfmSplat> splatsOf(const float* psf, int pixelsAcross, int lensletsAcross, int pixelsPerLenslet,
                               int rowsPerPeriod, double keep) {
  const std::size_t size = std::size_t(pixelsAcross) * pixelsAcross;
  std::vector<std::uint32_t> order;
  double total = 0;
  for (std::size_t k = 0; k < size; ++k)
    if (psf[k] > 0) order.push_back(std::uint32_t(k)), total += psf[k];
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return psf[a] > psf[b] || (psf[a] == psf[b] && a < b); });
  std::vector<LfmSplat> splats;
  const int centre = lensletsAcross / 2;
  double kept = 0;
  for (std::uint32_t k : order) {
    if (keep < 1 && kept >= keep * total) break;
    kept += psf[k];
    const int x = int(k % pixelsAcross), y = int(k / pixelsAcross);
    // The window's lenslet row r from the centre's is row r mod R of period floor(r / R).
    const int row = y / pixelsPerLenslet - centre, period = floorDivide(row, rowsPerPeriod);
    const int v = (row - period * rowsPerPeriod) * pixelsPerLenslet + y % pixelsPerLenslet;
    splats.push_back({.pixel = std::uint16_t(v * pixelsPerLenslet + x % pixelsPerLenslet),
                      .dx = std::int8_t(x / pixelsPerLenslet - centre),
                      .dy = std::int8_t(period),
                      .weight = psf[k]});
  }
  // In memory order of the pixels they land on: the projectors stream through them.
  std::sort(splats.begin(), splats.end(), [](const LfmSplat& a, const LfmSplat& b) {
    return std::tie(a.pixel, a.dy, a.dx) < std::tie(b.pixel, b.dy, b.dx);
  });
  return splats;
}

// Appends `set`'s splats (one slice or several) to `out`.
void appendSplats(const LfmPsfSet& set, double keep, LfmSparsePsf& out) {
  const std::size_t phases = set.grid.depthsUm.size() * set.grid.voxelsPerLenslet * set.voxelRows();
  std::vector<std::vector<LfmSplat>> each(phases);
  parallelFor(0, phases, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p)
      each[p] = splatsOf(set.values.data() + p * set.pixelsAcross * set.pixelsAcross, set.pixelsAcross,
                         set.lensletsAcross, set.grid.pixelsPerLenslet, set.optics.rowsPerPeriod(), keep);
  });
  if (out.begins.empty()) out.begins.push_back(0);
  for (const auto& splats : each) {
    out.splats.insert(out.splats.end(), splats.begin(), splats.end());
    out.begins.push_back(out.splats.size());
  }
  out.reach = std::max(out.reach, set.lensletsAcross / 2);
}

}  // namespace

LfmSparsePsf sparsePsf(const LfmPsfSet& set, double keep) {
  LfmSparsePsf out{.optics = set.optics, .pupil = set.pupil, .grid = set.grid, .keptEnergy = keep};
  appendSplats(set, keep, out);
  return out;
}

Result<LfmSparsePsf> computeSparsePsf(const LfmOptics& microscope, const LfmGrid& grid, double keep, PupilModel pupil,
                                      const ProgressCallback& progress) {
  LFCAM_TRY(validateLfmOptics(microscope));
  LFCAM_TRY(validateLfmGrid(grid));
  if (!(keep > 0 && keep <= 1)) return lfm::usage("PSF energy kept " + lfm::number(keep) + " outside (0, 1]");
  LfmSparsePsf out{
      .optics = frameOptics(microscope, grid.pixelsPerLenslet), .pupil = pupil, .grid = grid, .keptEnergy = keep};
  for (std::size_t d = 0; d < grid.depthsUm.size(); ++d) {
    LfmGrid slice = grid;
    slice.depthsUm = {grid.depthsUm[d]};
    const int lenslets = LfmPsf::lensletsFor(out.optics, grid.depthsUm[d]);
    if (lenslets / 2 > 127)
      return makeError(ErrorCode::Usage, "the PSF of a slice at " + std::to_string(grid.depthsUm[d]) +
                                             " um spreads over more than 255 lenslets: fewer or nearer slices");
    LFCAM_ASSIGN_OR_RETURN(LfmPsfSet set, computePsfSet(microscope, slice, lenslets, pupil));
    appendSplats(set, keep, out);
    if (progress) progress(double(d + 1) / grid.depthsUm.size());
  }
  return out;
}

}  // namespace lfcam
