// The light-field microscope's reconstruction at the size of issue 52's goal: a 1463 x 1273 frame
// at 19 pixels a lenslet (77 x 67 lenslets), 25 slices, one voxel a pixel (Prevedel et al.'s
// grid, the one fast-light-field's published 629 s CPU figure is for), 4 Richardson-Lucy
// iterations, on the optics of Wagner et al. 2019 (22.2x / 0.5 water, 520 nm, 125 um lenslets of
// 3125 um focal length, 6.5 um pixels). The frame is made by the forward model from beads.
//
//   build/bench/lfm_volume_bench [--psf PATH] [--keep E] [--slices N] [--iterations I]
//
// Prints the PSF's time and size (computed once, then read from PATH when it is there), the
// reconstruction's time per iteration and in all, the peak memory, and, in the same run, a
// memory copy of the volume as the floor a projection cannot beat.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "core/memory_floor.hpp"
#include "lfcam/lfm/projector.hpp"
#include "lfcam/lfm/reconstruct.hpp"
#include "lfcam/lfm/sparse_psf.hpp"

using namespace lfcam;

namespace {

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double peakMemoryGiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / (1024.0 * 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  std::string psfPath = "/tmp/lfcam-wagner-psf.h5";
  double keep = 0.95;
  int slices = 25, iterations = 4;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--psf")
      psfPath = argv[i + 1];
    else if (flag == "--keep")
      keep = std::atof(argv[i + 1]);
    else if (flag == "--slices")
      slices = std::atoi(argv[i + 1]);
    else if (flag == "--iterations")
      iterations = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: %s [--psf PATH] [--keep E] [--slices N] [--iterations I]\n", argv[0]);
      return 2;
    }
  }
  const LfmOptics optics{.magnification = 22.222,
                         .numericalAperture = 0.5,
                         .immersionIndex = 1.33,
                         .wavelengthNm = 520,
                         .tubeFocalLengthMm = 200,
                         .microlensPitchUm = 125,
                         .microlensFocalLengthUm = 3125,
                         .pixelSizeUm = 6.5,
                         .supersample = 3};
  LfmGrid grid{.pixelsPerLenslet = 19, .voxelsPerLenslet = 19};
  for (int z = 0; z < slices; ++z) grid.depthsUm.push_back(4.0 * (z - (slices - 1) / 2.0));  // 4 um apart

  auto start = std::chrono::steady_clock::now();
  Result<LfmSparsePsf> psf = readPsfCache(psfPath, optics, grid, keep);
  const bool cached = bool(psf);
  if (!cached) {
    psf = computeSparsePsf(optics, grid, keep);
    if (!psf) {
      std::fprintf(stderr, "%s\n", psf.error().message.c_str());
      return 1;
    }
    if (Status written = writePsfCache(psf.value(), psfPath); !written)
      std::fprintf(stderr, "%s\n", written.error().message.c_str());
  }
  const double psfSeconds = seconds(start);
  std::printf(
      "PSF: %d slices x %d voxel phases, %zu splats (%.0f a PSF, %.0f %% of the energy), reach %d lenslets, "
      "%s in %.1f s, %.0f MB on disk\n",
      slices, 19 * 19, psf->splats.size(), double(psf->splats.size()) / (slices * 361.0), keep * 100, psf->reach,
      cached ? "read" : "computed", psfSeconds, std::filesystem::file_size(psfPath) / 1e6);

  const LfmProjector projector(psf.value(), 77, 67);
  Volume truth = projector.emptyVolume();
  std::mt19937 random(2019);
  for (int bead = 0; bead < 300; ++bead)
    truth.at(int(random() % truth.width()), int(random() % truth.height()), int(random() % truth.depth())) = 1;
  const Image frame = simulateLfmFrame(projector, truth, 0.001, 5000, 1);
  std::printf("frame %d x %d, volume %d x %d x %d (%.0f MB)\n", frame.width(), frame.height(), truth.width(),
              truth.height(), truth.depth(), truth.voxels().size() * 4 / 1e6);

  start = std::chrono::steady_clock::now();
  const Image forward = projector.forward(truth);
  const double forwardSeconds = seconds(start);
  start = std::chrono::steady_clock::now();
  const Volume back = projector.backward(frame);
  const double backwardSeconds = seconds(start);
  MemoryFloor floor(double(truth.voxels().size()) * 4);
  const double floorSeconds = floor.measure();

  start = std::chrono::steady_clock::now();
  const auto result = reconstructVolume(projector, frame, {.iterations = iterations, .background = 0.001});
  const double total = seconds(start);
  if (!result) {
    std::fprintf(stderr, "%s\n", result.error().message.c_str());
    return 1;
  }
  std::printf("forward projection %.2f s, back projection %.2f s; a copy of the volume %.4f s (%.0fx, %.0fx it)\n",
              forwardSeconds, backwardSeconds, floorSeconds, forwardSeconds / floorSeconds,
              backwardSeconds / floorSeconds);
  std::printf(
      "Richardson-Lucy, %d iterations: %.1f s (%.1f s an iteration), residual %.3f -> %.3f; peak memory "
      "%.2f GiB\n",
      iterations, total, total / iterations, result->residuals.front(), result->residuals.back(), peakMemoryGiB());
  std::printf("against fast-light-field's published 629 s on a CPU: %.1fx faster\n", 629 / total);
  return 0;
}
