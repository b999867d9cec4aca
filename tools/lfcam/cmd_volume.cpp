// lfcam volume FRAME [--white W --dark D] --optics OPTICS.json | --objective 60x/1.2/water ...
//               --slices N --um-per-slice Z [--supersample K] [--iterations I] [--psf CACHE] -o VOLUME.tif:
// a light-field microscope frame -> a 3D volume by Richardson-Lucy through the wave-optics PSF
// (volume_request.hpp), written as a 32-bit TIFF stack Fiji opens with its voxel size, or HDF5.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.hpp"
#include "core/parallel.hpp"
#include "lfcam/io/volume_io.hpp"
#include "lfcam/lfm/volume_request.hpp"
#include "progress_bar.hpp"

namespace lfcam::cli {

namespace {

volatile std::sig_atomic_t interrupted = 0;

extern "C" void onInterrupt(int) {
  interrupted = 1;
  requestCancellation(true);
}

// Ctrl-C while it lives stops the work at the next parallel step instead of killing the process
// half-way through a write; a second Ctrl-C kills as usual.
class InterruptGuard {
 public:
  InterruptGuard() {
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &previous_);
  }
  ~InterruptGuard() {
    sigaction(SIGINT, &previous_, nullptr);
    requestCancellation(false);
  }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  struct sigaction previous_ {};
};

// The default cache: beside the frame, named by its settings (psfCacheName).
std::string defaultPsfPath(const std::string& frame, const LfmVolumeRequest& request) {
  return (std::filesystem::path(frame).parent_path() / psfCacheName(request)).string();
}

}  // namespace

void addVolumeCommand(CLI::App& app, Job& job) {
  struct Options {
    InputOptions input;
    LfmVolumeSettings settings;
    std::string output, psf;
    bool noCache = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "volume", "reconstruct a 3D volume from a light-field microscope frame (Richardson-Lucy, wave optics)");
  addInputOptions(*command, options->input);
  command->add_option(
      "--optics", options->settings.opticsFile,
      "microscope settings: napari-LF's metadata.txt or .lfc calibration, or a JSON object of its calibrate keys");
  command->add_option("--objective", options->settings.objective,
                      "MAGx/NA/MEDIUM, e.g. 60x/1.2/water (medium: water, oil, "
                      "glycerol, air or a refractive index)");
  command->add_option("--wavelength", options->settings.wavelengthNm, "emission wavelength, nm");
  command->add_option("--tube-lens", options->settings.tubeLensMm, "tube lens focal length, mm (default 200)");
  command->add_option("--pitch", options->settings.pitchUm, "microlens pitch, um");
  command->add_option("--microlens-array", options->settings.microlensArray,
                      "square (default) or hexagonal: a hexagonal frame's lenslets each N x N pixels over a pitch x "
                      "sqrt(3)/2 pitch brick, odd rows shifted half a pitch right");
  command->add_option("--microlens-focal-length", options->settings.microlensFocalLengthUm,
                      "microlens focal length, um");
  command->add_option("--pixel-size", options->settings.pixelSizeUm, "camera pixel size, um");
  command->add_option("--slices", options->settings.slices, "number of z-slices");
  command->add_option("--um-per-slice", options->settings.umPerSlice, "slice spacing in the specimen, um (default 1)");
  command->add_option("--z-center", options->settings.zCenterUm,
                      "depth of the middle slice from the focal plane, um (default 0)");
  command->add_option("--supersample", options->settings.supersample,
                      "voxels across a lenslet (napari-LF's supersample; "
                      "default 1)");
  command->add_option("--solver", options->settings.solver, "rl (Richardson-Lucy, default) or backprojection");
  command->add_option("--iterations", options->settings.iterations, "Richardson-Lucy iterations (default 8)");
  command->add_option("--tolerance", options->settings.tolerance,
                      "stop when the volume changes by less than this fraction");
  command->add_option("--background", options->settings.background,
                      "background level in the frame's units (default 0)");
  command->add_option("--tv", options->settings.tvWeight,
                      "total-variation regularisation weight, in [0, 1) (default 0)");
  command->add_option("--psf", options->psf, "PSF cache file (default: lfcam-psf-<settings>.h5 beside the frame)");
  command->add_flag("--no-psf-cache", options->noCache, "compute the PSF and keep it nowhere");
  command->add_option("--psf-energy", options->settings.psfEnergy, "fraction of each PSF's energy kept (default 0.95)");
  command->add_option("-o,--output", options->output, "output volume: NAME.tif (32-bit stack) or NAME.h5")->required();
  command->callback([options, &job] {
    job = [options]() -> Status {
      const Options& o = *options;
      LFCAM_ASSIGN_OR_RETURN(LfmVolumeRequest request, volumeRequestFrom(o.settings));
      // A raw's grid has the optics' packing; a hexagonal array's raw is decoded into the bricks
      // its PSF is computed on.
      InputOptions input = o.input;
      const bool hexagonal = request.optics.array == MicrolensLayout::Hexagonal;
      input.decode.packing = hexagonal ? Packing::Hexagonal : Packing::Square;
      if (hexagonal && input.decodesRaw()) {
        if (input.decode.sampling == Sampling::IntegralPitch)
          return makeError(ErrorCode::Usage, "--sampling integral: a hexagonal array's raw is sampled on its bricks");
        input.decode.sampling = Sampling::Bricks;
      }
      LFCAM_TRY(checkVolumePath(o.output));
      if (!o.noCache) request.psfPath = o.psf.empty() ? defaultPsfPath(o.input.path, request) : o.psf;
      // Beside a frame in a read-only folder (a shared data set) the default cache cannot be kept.
      if (o.psf.empty() && !request.psfPath.empty() && !std::filesystem::exists(request.psfPath)) {
        const auto folder = std::filesystem::path(request.psfPath).parent_path();
        const auto where = folder.empty() ? std::filesystem::path(".") : folder;
        std::error_code error;
        const auto permissions = std::filesystem::status(where, error).permissions();
        // Root may write anywhere: a folder without write bits is read-only by intent all the same.
        const auto writeBits = std::filesystem::perms::owner_write | std::filesystem::perms::group_write |
                               std::filesystem::perms::others_write;
        if (error || access(where.c_str(), W_OK) != 0 || (permissions & writeBits) == std::filesystem::perms::none) {
          std::fprintf(stderr, "lfcam: %s is not writable: the PSF is computed, not cached (--psf FILE keeps it)\n",
                       folder.c_str());
          request.psfPath.clear();
        }
      }

      InterruptGuard guard;
      const auto stopped = [&] { return makeError(ErrorCode::Io, o.input.path + ": interrupted; nothing written"); };
      Result<LightField> loaded = loadInput(input);
      if (interrupted) return stopped();
      LFCAM_ASSIGN_OR_RETURN(const LightField frame, std::move(loaded));
      Result<LfmVolumeResult> result = makeError(ErrorCode::Io, "");
      {
        ProgressBar bar("volume " + o.input.path);
        result = reconstructVolume(frame, request, o.input.path, [&](double f) { bar(f); });
      }
      if (interrupted) return stopped();
      if (!result) return result.error();
      const LfmReconstruction& r = result->reconstruction;
      const std::string psfNote =
          request.psfPath.empty()
              ? std::string("computed")
              : std::string(result->psfFromCache ? "read from " : "computed into ") + request.psfPath;
      std::printf("%s: %d x %d x %d voxels of %.3g x %.3g x %.3g um; PSF %s (%zu splats); ", o.output.c_str(),
                  r.volume.width(), r.volume.height(), r.volume.depth(), r.volume.voxelWidthUm, r.volume.voxelHeightUm,
                  r.volume.voxelDepthUm, psfNote.c_str(), result->psfSplats);
      if (request.reconstruct.solver == LfmSolver::RichardsonLucy)
        std::printf("%d Richardson-Lucy iterations, residual %.4f -> %.4f\n", r.iterations, r.residuals.front(),
                    r.residuals.back());
      else
        std::printf("back-projection\n");
      return writeVolume(o.output, r.volume);
    };
  });
}

}  // namespace lfcam::cli
