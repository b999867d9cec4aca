// Forward and back projection between a volume and a rectified light-field microscope frame
// (Broxton et al. 2013, section 4): the frame is the sum over voxels of each voxel's PSF placed at
// its lenslet, and the back projection is that operator's transpose. The lenslets repeat, so one
// PSF per slice and voxel of a lenslet serves them all (LfmSparsePsf).
//
// Frame: one channel, lensletsX N x lensletsY N pixels, lenslet (s, t) at pixels [s N, (s + 1) N)
// x [t N, (t + 1) N). Volume: lensletsX K x lensletsY K voxels and one slice per PSF slice, voxel
// (s K + i, t K + j) being voxel (i, j) of lenslet (s, t) (psf.hpp's LfmGrid). Light from beyond
// the frame's edges is not modelled: the volume covers the frame's lenslets only. A hexagonal
// array repeats every two rows of lenslets (its odd rows shifted): the PSFs are those of the
// voxels of a pitch x two-rows period, and lensletsY must be even.
#pragma once

#include <memory>

#include "lfcam/core/image.hpp"
#include "lfcam/core/volume.hpp"
#include "lfcam/lfm/sparse_psf.hpp"

namespace lfcam {

class LfmProjector {
 public:
  // Keeps a reference to `psf`, which must outlive the projector. lensletsY: a multiple of
  // psf.optics.rowsPerPeriod().
  LfmProjector(const LfmSparsePsf& psf, int lensletsX, int lensletsY);
  ~LfmProjector();
  LfmProjector(LfmProjector&&) noexcept;
  LfmProjector& operator=(LfmProjector&&) noexcept;

  int lensletsX() const;
  int lensletsY() const;
  const LfmSparsePsf& psf() const;

  // The frame of `volume` (its dimensions as above; the voxel sizes are not read).
  Image forward(const Volume& volume) const;
  // The transpose: <forward(v), f> = <v, backward(f)> for every v and f. Its voxel sizes are the
  // grid's.
  Volume backward(const Image& frame) const;

  // backward() of a frame of ones, how much of the frame each voxel reaches, from the splats'
  // weights summed by lenslet offset instead of a projection.
  Volume sensitivity() const;

  // A volume of the grid's dimensions and voxel sizes, zero-filled.
  Volume emptyVolume() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace lfcam
