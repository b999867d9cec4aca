// The PSF's stages one by one (psf.hpp gives the contract), with their float64 references: the
// tests hold each fast stage against its reference.
#pragma once

#include <complex>
#include <memory>
#include <vector>

#include "lfcam/lfm/optics.hpp"
#include "lfcam/lfm/psf.hpp"

namespace lfcam::lfm {

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n; exact for polynomials of degree
// 2n - 1).
void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// The Debye integral of psf.hpp's debyeField for one depth, its quadrature chosen once for radii
// up to maxRadiusUm; field(r) for any r in [0, maxRadiusUm].
class DebyeIntegral {
 public:
  DebyeIntegral(const LfmOptics& optics, double depthUm, double maxRadiusUm, PupilModel pupil);
  std::complex<double> field(double radiusUm) const;
  int nodeCount() const { return int(rho_.size()); }

 private:
  double beta_ = 0;  // v = beta r
  std::vector<double> rho_;
  std::vector<std::complex<double>> weight_;  // quadrature weight * C * A(rho) e^{i phi(rho)} * rho
};

// The sensor pixels across a window of lensletsAcross lenslets: the odd count covering them.
int windowPixels(const LfmOptics& optics, int lensletsAcross);

// The pixels a rectified hexagonal frame has under each lenslet along x (optics.hpp's
// pixelAspect and psf.hpp's frameOptics): N when pitch / pixel is a whole N and N pixels make a
// row of lenslets, the pixels then tiling each lenslet's pitch x row-pitch brick; 0 otherwise.
int hexagonalBrickPixels(const LfmOptics& optics);

// Sample i of an n-sample axis sits at (i - (n - 1) / 2) * spacing.
inline double sampleCoordinate(int i, int n, double spacing) { return (i - 0.5 * (n - 1)) * spacing; }

// The native image's radial profile for one depth, sampled every `step` out to a radius: the
// Debye integral evaluated once and shared by every point of that depth (only the centre moves).
struct RadialProfile {
  double depthUm = 0, step = 0;
  std::vector<std::complex<double>> values;
  double maxRadiusUm() const { return step * double(values.size() - 2); }
  // Linear interpolation: step is the grid's spacing / 16, so its error is (h^2 / 8) |U''|, with
  // |U''| <= (2 pi kappa)^2 |U| and 2 kappa dx < 1: below 1e-3 of the field's magnitude.
  std::complex<double> at(double radiusUm) const;
};
RadialProfile radialProfile(const LfmOptics& optics, PupilModel pupil, double depthUm, double maxRadiusUm);

// The largest distance from the image of `point` to a sample of the n x n grid.
double maxRadiusOnGrid(const LfmOptics& optics, const LfmPoint& point, int n);

// The native image field on the n x n grid: from the profile (fast; the profile must reach
// maxRadiusOnGrid), or the Debye integral at every sample (reference).
std::vector<std::complex<double>> nativeFieldFromProfile(const LfmOptics& optics, const RadialProfile& profile,
                                                         const LfmPoint& point, int n);
std::vector<std::complex<double>> nativeFieldDirect(const LfmOptics& optics, PupilModel pupil, const LfmPoint& point,
                                                    int n);

// The centre of the lenslet whose cell holds the image-side point (x, y), as optics.hpp places them.
struct LensletCentre {
  double xUm, yUm;
};
LensletCentre nearestLenslet(const LfmOptics& optics, double xUm, double yUm);

// Multiplies the n x n field by the microlens array's transmission: exp(-i pi d^2 / (lambda f))
// within each lenslet's aperture (d: distance to its centre; its cell shrunk to the fill factor),
// 0 in the opaque border.
template <class T>
void applyMicrolenses(const LfmOptics& optics, int n, std::complex<T>* field);

// Fresnel propagation over `distanceUm` of an n x n field sampled every spacingX along x and
// spacingY along y by its transfer function exp(-i pi lambda z (fx^2 + fy^2)) (the constant
// exp(ikz) dropped), on FFTW float plans made once; periodic. propagate() may run on several
// threads at once.
class FresnelTransfer {
 public:
  FresnelTransfer(int n, double spacingXUm, double spacingYUm, double wavelengthUm, double distanceUm);
  ~FresnelTransfer();
  FresnelTransfer(const FresnelTransfer&) = delete;
  FresnelTransfer& operator=(const FresnelTransfer&) = delete;
  void propagate(std::complex<float>* field) const;  // in place, n * n

 private:
  int n_;
  std::vector<std::complex<float>> transfer_;  // H / n^2, FFT order
  void* forward_ = nullptr;
  void* inverse_ = nullptr;
};

// The reference: the Fresnel diffraction integral summed directly, in float64, aperiodic:
// U2(x) = dx dy / (i lambda z) sum U1(x') exp(i pi |x - x'|^2 / (lambda z)). O(n^4).
std::vector<std::complex<double>> fresnelDirect(const std::vector<std::complex<double>>& field, int n,
                                                double spacingXUm, double spacingYUm, double wavelengthUm,
                                                double distanceUm);

// |U|^2 dx dy summed over each supersample x supersample block: the pixels' energies. On a
// rectified hexagonal frame (hexagonalBrickPixels N > 0) the window's rows of N pixels alternate,
// its middle one unshifted: every other row's pixels are read half a pitch (N supersample / 2
// samples) further along x, periodically, as that row's lenslets sit.
Image integratePixels(const std::complex<float>* field, int n, const LfmOptics& optics);

}  // namespace lfcam::lfm
