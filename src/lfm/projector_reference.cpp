#include "lfm/projector_reference.hpp"

namespace lfcam::lfm {

namespace {

// Calls visit(voxel index, frame index, PSF value) for every pair a PSF links.
template <class Visit>
void forEachLink(const LfmPsfSet& set, int lensletsX, int lensletsY, Visit&& visit) {
  const int k = set.grid.voxelsPerLenslet, n = set.grid.pixelsPerLenslet, w = set.pixelsAcross;
  const int rows = set.optics.rowsPerPeriod(), voxelRows = set.voxelRows();
  const int width = lensletsX * k, height = lensletsY * k, frameWidth = lensletsX * n, frameHeight = lensletsY * n;
  const int centre = set.lensletsAcross / 2;
  for (int z = 0; z < int(set.grid.depthsUm.size()); ++z)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float* psf = set.psf(z, x % k, y % voxelRows);
        // The window's pixel (0, 0) is pixel (0, 0) of the lenslet `centre` lenslets up and left
        // of the first lenslet of the voxel's period.
        const int left = (x / k - centre) * n, top = (y / voxelRows * rows - centre) * n;
        for (int py = 0; py < w; ++py)
          for (int px = 0; px < w; ++px) {
            const int fx = left + px, fy = top + py;
            if (fx < 0 || fy < 0 || fx >= frameWidth || fy >= frameHeight) continue;
            visit((std::size_t(z) * height + y) * width + x, std::size_t(fy) * frameWidth + fx,
                  double(psf[py * w + px]));
          }
      }
}

}  // namespace

std::vector<double> forwardDirect(const LfmPsfSet& set, const std::vector<double>& volume, int lensletsX,
                                  int lensletsY) {
  const int n = set.grid.pixelsPerLenslet;
  std::vector<double> frame(std::size_t(lensletsX) * n * lensletsY * n, 0.0);
  forEachLink(set, lensletsX, lensletsY,
              [&](std::size_t voxel, std::size_t pixel, double h) { frame[pixel] += h * volume[voxel]; });
  return frame;
}

std::vector<double> backwardDirect(const LfmPsfSet& set, const std::vector<double>& frame, int lensletsX,
                                   int lensletsY) {
  const int k = set.grid.voxelsPerLenslet;
  std::vector<double> volume(std::size_t(lensletsX) * k * lensletsY * k * set.grid.depthsUm.size(), 0.0);
  forEachLink(set, lensletsX, lensletsY,
              [&](std::size_t voxel, std::size_t pixel, double h) { volume[voxel] += h * frame[pixel]; });
  return volume;
}

}  // namespace lfcam::lfm
