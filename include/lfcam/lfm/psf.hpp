// The wave-optics point-spread function of a light-field microscope (Broxton et al. 2013,
// section 3): a point source in the specimen, its field at the native image plane by the Debye
// integral of the objective (Equation 3), times the microlens array's phase mask (Equation 6),
// carried to the sensor by Fresnel propagation over the microlens focal length (Equation 7), its
// intensity integrated over the sensor pixels (Equation 8). LfmOptics (optics.hpp) describes the
// microscope.
//
// Frames. A point at (x, y, z) micrometres in the specimen: z along the optical axis from the
// native object plane (z = 0 is in focus), growing toward the objective as napari-LF's does (a real
// GUV capture reconstructs as napari-LF's volume with this sign, slices reversed with the other), its image centred at
// (M x, M y) on the native image plane, which is the microlens plane (the image is not inverted: the sensor's readout
// is assumed to turn it upright). One lenslet is centred on the optical axis. The sensor's pixels form a square centred
// on the axis (its centre pixel on it when odd; a rectified frame of N pixels a lenslet has N times the lenslets, the
// axis between pixels when N is even). A rectified hexagonal frame's pixels tile each lenslet's brick, pitch wide and
// a row of lenslets high (frameOptics): the window's rows of bricks alternate as the array's rows do, every other one
// half a pitch along x (the window periodic across its edges).
//
// Normalisation. The field at the native image plane carries unit energy: the integral of
// |U|^2 over that plane (square micrometres) is 1 at every depth. A PSF pixel holds the energy
// landing on it, so a PSF sums to the part of that unit energy falling within its window (less the
// light an opaque fill-factor border stops).
#pragma once

#include <complex>
#include <memory>
#include <span>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/lfm/optics.hpp"

namespace lfcam {

// The objective's pupil (the amplitude over the exit pupil, rho = sin(theta) / sin(alpha)):
// AbbeSine is Broxton's Equation 3, an aplanatic objective's sqrt(cos theta) apodization and the
// exact defocus phase k z (1 - cos theta); Paraxial is the textbook low-NA limit (uniform pupil,
// defocus k z sin^2(alpha) rho^2 / 2), whose in-focus intensity is exactly the Airy pattern.
enum class PupilModel { AbbeSine, Paraxial };

// The field at the native image plane, at image-side distances `radiiUm` from the image of a point
// at depth `depthUm` (object side): the radial Debye integral over rho in [0, 1] by Gauss-Legendre
// quadrature, in float64, with nodes enough for the fastest oscillation (J0(v rho) and the defocus
// phase). v = 2 pi r NA / (lambda M). Usage error when the optics are invalid.
Result<std::vector<std::complex<double>>> debyeField(const LfmOptics& optics, double depthUm,
                                                     std::span<const double> radiiUm,
                                                     PupilModel pupil = PupilModel::AbbeSine);

struct LfmPoint {
  double xUm = 0, yUm = 0, zUm = 0;  // in the specimen (see Frames)
};

// PSFs of points on a window of `lensletsAcross` x `lensletsAcross` lenslets (odd; rows of them for
// a hexagonal frame) around the optical axis: the window's sensor pixels, pixelsAcross() square. Plans its FFT once;
// psf() may be called from several threads at once. A point's native image larger than the window wraps around it (the
// propagation is periodic): choose the window by lensletsFor().
class LfmPsf {
 public:
  // Usage error for invalid optics, an even or non-positive lensletsAcross, a sample spacing
  // that aliases the native image or the microlenses' phase (raise supersample), or a hexagonal
  // frame whose shifted rows fall between samples (N supersample odd).
  static Result<LfmPsf> create(const LfmOptics& optics, int lensletsAcross, PupilModel pupil = PupilModel::AbbeSine);
  // The odd number of lenslets (rows of them) across a window holding the geometric blur of points
  // of the array's period at depths up to |maxDepthUm|: its radius M |z| tan(alpha), a period's
  // rows of margin on each side.
  static int lensletsFor(const LfmOptics& optics, double maxDepthUm);

  LfmPsf(LfmPsf&&) noexcept;
  LfmPsf& operator=(LfmPsf&&) noexcept;
  ~LfmPsf();

  const LfmOptics& optics() const;
  int pixelsAcross() const;   // sensor pixels across the window
  int samplesAcross() const;  // field samples across: pixelsAcross() * supersample

  // The sensor image of one point: pixelsAcross() square, one channel, energy per pixel.
  Image psf(const LfmPoint& point) const;

  // The stages, for tests and for callers wanting fields: the field at the native image plane
  // on the samplesAcross() square grid (sample (i, j) at ((i - (n - 1) / 2) sampleSpacingUm(),
  // (j - (n - 1) / 2) sampleHeightUm())), and at the sensor (after the microlens mask).
  std::vector<std::complex<double>> nativeField(const LfmPoint& point) const;
  std::vector<std::complex<float>> sensorField(const LfmPoint& point) const;

 private:
  struct State;
  explicit LfmPsf(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The volume a reconstruction samples. The frame is rectified to N x N pixels a lenslet, lenslet
// (s, t) covering pixels [s N, (s + 1) N) x [t N, (t + 1) N); the volume holds K x K voxels a
// lenslet across its slices, voxel i of a lenslet at ((i + 0.5) / K - 0.5) pitch / M from the
// lenslet's centre in the specimen (napari-LF's layout; K = N is Prevedel et al.'s, a voxel a
// pixel). A hexagonal array's frame is the same blocks, each its lenslet's brick (psf.hpp's
// Frames), odd rows t shifted half a pitch toward +x; its volume's voxels are pitch / (K M) wide
// and row pitch / (K M) high, voxel (x, y) at (((x + 0.5) / K - 0.5) pitch, ((y + 0.5) / K - 0.5)
// row pitch) / M from lenslet (0, 0): a regular grid, not centred on the shifted rows' lenslets.
struct LfmGrid {
  int pixelsPerLenslet = 15;     // N: a lenslet's centre on a pixel's centre when odd, between two when even
  int voxelsPerLenslet = 1;      // K in [1, N]: napari-LF's "supersample"
  std::vector<double> depthsUm;  // each slice's depth in the specimen (z = 0 in focus)

  // Voxel i of a lenslet along x, and voxel j of the array's period along y (of rowsPerPeriod()
  // rows), from the centre of its first lenslet, in the specimen.
  double voxelOffsetUm(const LfmOptics& optics, int i) const {
    return ((i + 0.5) / voxelsPerLenslet - 0.5) * optics.microlensPitchUm / optics.magnification;
  }
  double voxelRowOffsetUm(const LfmOptics& optics, int j) const {
    return ((j + 0.5) / voxelsPerLenslet - 0.5) * optics.rowPitchUm() / optics.magnification;
  }
};
// Ok, or one line: N outside [2, 255], K outside [1, N], no slices, a depth not finite.
Status validateLfmGrid(const LfmGrid& grid);

// The optics of the rectified frame: the microscope's, its pixel the pitch / N of a rectified one;
// for a hexagonal array the row pitch / N high (pixelAspect sqrt(3)/2) and the supersample raised
// by one when N supersample is odd (LfmPsf::create).
LfmOptics frameOptics(const LfmOptics& optics, int pixelsPerLenslet);

// The PSFs Broxton's forward operator H needs (section 4): every slice and every voxel of the
// array's period (the centre lenslet's; a hexagonal array's two rows, the centre lenslet's and
// the row above it: K x 2K), on the rectified frame's pixels over a window of lensletsAcross
// lenslets. Values: [depth][j][i][y][x], pixelsAcross square each (pixelsAcross = lensletsAcross N).
struct LfmPsfSet {
  LfmOptics optics;  // frameOptics of the microscope
  PupilModel pupil = PupilModel::AbbeSine;
  LfmGrid grid;
  int lensletsAcross = 0, pixelsAcross = 0;
  std::vector<float> values;

  int voxelRows() const { return optics.rowsPerPeriod() * grid.voxelsPerLenslet; }  // j in [0, voxelRows())
  LfmPoint point(int depth, int i, int j) const;                                    // voxel (i, j) of the period
  const float* psf(int depth, int i, int j) const;
};

// The grid's and LfmPsf::create's refusals; lensletsAcross 0 picks LfmPsf::lensletsFor the
// deepest slice. A square array's symmetry (mirrors and the diagonal) gives 7 of 8 phases by
// copying; a hexagonal array's phases are each computed.
Result<LfmPsfSet> computePsfSet(const LfmOptics& microscope, const LfmGrid& grid, int lensletsAcross = 0,
                                PupilModel pupil = PupilModel::AbbeSine);

}  // namespace lfcam
