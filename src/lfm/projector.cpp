#include "lfcam/lfm/projector.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/parallel.hpp"
#include "core/target_clones.hpp"

namespace lfcam {

namespace {

// Lenslets a tile across and down: one row of a tile is one AVX2 register of floats.
constexpr int kTile = 8;
constexpr int kTileSize = kTile * kTile;

// Planes over the lenslet grid rounded up to whole tiles, with `reach` lenslets of zeros around:
// a splat's offset then never leaves its plane.
struct PaddedPlanes {
  int reach = 0, tilesX = 0, tilesY = 0, width = 0, height = 0;
  std::size_t planes = 0;
  std::vector<float> values;

  PaddedPlanes(int lensletsX, int lensletsY, int reach_, std::size_t planes_)
      : reach(reach_),
        tilesX((lensletsX + kTile - 1) / kTile),
        tilesY((lensletsY + kTile - 1) / kTile),
        width(tilesX * kTile + 2 * reach_),
        height(tilesY * kTile + 2 * reach_),
        planes(planes_),
        values(planes_ * width * height, 0.0f) {}
  float* at(std::size_t plane, int x, int y) {
    return values.data() + (plane * height + y + reach) * width + x + reach;
  }
  const float* at(std::size_t plane, int x, int y) const {
    return values.data() + (plane * height + y + reach) * width + x + reach;
  }
};

// One row of a tile: kTile floats, one AVX2 register (two SSE ones in the baseline clone).
typedef float Row __attribute__((vector_size(kTile * sizeof(float))));

// The forward projection of one (slice, voxel phase) plane over one tile: each splat adds its
// weight times the voxels `d` lenslets back (origin - d) to its pixel's tile of sums. The splats
// come sorted by pixel: each run of one pixel keeps that pixel's sums in registers.
LFCAM_CLONES void forwardPhase(float* __restrict sums, const float* __restrict origin, int stride,
                               const LfmSplat* splat, const LfmSplat* end) {
  while (splat != end) {
    const int pixel = splat->pixel;
    float* out = sums + std::size_t(pixel) * kTileSize;
    Row acc[kTile];
    std::memcpy(acc, out, sizeof acc);
    for (; splat != end && splat->pixel == pixel; ++splat) {
      const float* in = origin - splat->dy * stride - splat->dx;
      for (int r = 0; r < kTile; ++r) {
        Row row;
        std::memcpy(&row, in + r * stride, sizeof row);
        acc[r] += splat->weight * row;
      }
    }
    std::memcpy(out, acc, sizeof acc);
  }
}

// The back projection into one (slice, voxel phase) plane over one tile: the sum over its splats
// of the weight times the frame's plane of the splat's pixel `d` lenslets on. `local` holds every
// pixel's plane around the tile, `planeSize` floats apart, origin at the tile's first lenslet.
LFCAM_CLONES void backwardPhase(float* __restrict sums, const float* __restrict local, std::size_t planeSize,
                                int stride, const LfmSplat* splat, const LfmSplat* end) {
  Row acc[kTile] = {};
  for (; splat != end; ++splat) {
    const float* in = local + splat->pixel * planeSize + splat->dy * stride + splat->dx;
    for (int r = 0; r < kTile; ++r) {
      Row row;
      std::memcpy(&row, in + r * stride, sizeof row);
      acc[r] += splat->weight * row;
    }
  }
  std::memcpy(sums, acc, sizeof acc);
}

}  // namespace

struct LfmProjector::State {
  const LfmSparsePsf* psf = nullptr;
  int lensletsX = 0, lensletsY = 0;
  int n = 0, k = 0, slices = 0;

  std::size_t phases() const { return std::size_t(slices) * k * k; }
};

LfmProjector::LfmProjector(const LfmSparsePsf& psf, int lensletsX, int lensletsY)
    : state_(std::make_unique<State>(State{.psf = &psf,
                                           .lensletsX = lensletsX,
                                           .lensletsY = lensletsY,
                                           .n = psf.grid.pixelsPerLenslet,
                                           .k = psf.grid.voxelsPerLenslet,
                                           .slices = int(psf.grid.depthsUm.size())})) {}
LfmProjector::~LfmProjector() = default;
LfmProjector::LfmProjector(LfmProjector&&) noexcept = default;
LfmProjector& LfmProjector::operator=(LfmProjector&&) noexcept = default;

int LfmProjector::lensletsX() const { return state_->lensletsX; }
int LfmProjector::lensletsY() const { return state_->lensletsY; }
const LfmSparsePsf& LfmProjector::psf() const { return *state_->psf; }

Volume LfmProjector::emptyVolume() const {
  const State& s = *state_;
  Volume volume(s.lensletsX * s.k, s.lensletsY * s.k, s.slices);
  const LfmGrid& grid = s.psf->grid;
  volume.voxelWidthUm = s.psf->optics.microlensPitchUm / (s.psf->optics.magnification * s.k);
  volume.firstSliceUm = grid.depthsUm.front();
  volume.voxelDepthUm = grid.depthsUm.size() > 1 ? grid.depthsUm[1] - grid.depthsUm[0] : 1;
  return volume;
}

Volume LfmProjector::sensitivity() const {
  const State& s = *state_;
  const int k = s.k, reach = s.psf->reach, side = 2 * reach + 1;
  Volume volume = emptyVolume();
  parallelFor(0, s.phases(), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> byOffset(std::size_t(side) * side), byRow(std::size_t(s.lensletsX) * side);
    for (std::size_t p = begin; p < end; ++p) {
      const int z = int(p / (k * k)), j = int(p / k % k), i = int(p % k);
      std::fill(byOffset.begin(), byOffset.end(), 0.0);
      for (const LfmSplat& splat : s.psf->of(z, i, j))
        byOffset[std::size_t(splat.dy + reach) * side + splat.dx + reach] += splat.weight;
      // Lenslet L reaches L + d when that lies on the frame, along x and along y apart.
      for (int x = 0; x < s.lensletsX; ++x)
        for (int dy = 0; dy < side; ++dy) {
          double sum = 0;
          for (int dx = 0; dx < side; ++dx)
            if (x + dx - reach >= 0 && x + dx - reach < s.lensletsX) sum += byOffset[std::size_t(dy) * side + dx];
          byRow[std::size_t(x) * side + dy] = sum;
        }
      for (int y = 0; y < s.lensletsY; ++y)
        for (int x = 0; x < s.lensletsX; ++x) {
          double sum = 0;
          for (int dy = 0; dy < side; ++dy)
            if (y + dy - reach >= 0 && y + dy - reach < s.lensletsY) sum += byRow[std::size_t(x) * side + dy];
          volume.at(x * k + i, y * k + j, z) = float(sum);
        }
    }
  });
  return volume;
}

Image LfmProjector::forward(const Volume& volume) const {
  const State& s = *state_;
  const int k = s.k, n = s.n;
  // The volume as one padded plane per (slice, voxel phase) over the lenslets.
  PaddedPlanes in(s.lensletsX, s.lensletsY, s.psf->reach, s.phases());
  parallelFor(0, s.phases(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const int z = int(p / (k * k)), j = int(p / k % k), i = int(p % k);
      for (int t = 0; t < s.lensletsY; ++t) {
        const float* row = volume.slice(z) + std::size_t(t * k + j) * volume.width() + i;
        float* out = in.at(p, 0, t);
        for (int x = 0; x < s.lensletsX; ++x) out[x] = row[std::size_t(x) * k];
      }
    }
  });
  Image frame(s.lensletsX * n, s.lensletsY * n, 1);
  const int pixels = n * n;
  const std::size_t tiles = std::size_t(in.tilesX) * in.tilesY;
  parallelFor(0, tiles, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> sums(std::size_t(pixels) * kTileSize);
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int x0 = int(tile % in.tilesX) * kTile, y0 = int(tile / in.tilesX) * kTile;
      std::fill(sums.begin(), sums.end(), 0.0f);
      for (std::size_t p = 0; p < s.phases(); ++p) {
        const int z = int(p / (k * k)), j = int(p / k % k), i = int(p % k);
        const float* origin = in.at(p, x0, y0);
        // A voxel at lenslet L lights lenslet L + d: the tile at L reads the voxels at L - d.
        const auto splats = s.psf->of(z, i, j);
        forwardPhase(sums.data(), origin, in.width, splats.data(), splats.data() + splats.size());
      }
      for (int c = 0; c < pixels; ++c) {
        const int u = c % n, v = c / n;
        for (int r = 0; r < kTile && y0 + r < s.lensletsY; ++r)
          for (int x = 0; x < kTile && x0 + x < s.lensletsX; ++x)
            frame.at((x0 + x) * n + u, (y0 + r) * n + v, 0) = sums[std::size_t(c) * kTileSize + r * kTile + x];
      }
    }
  });
  return frame;
}

Volume LfmProjector::backward(const Image& frame) const {
  const State& s = *state_;
  const int k = s.k, n = s.n, pixels = n * n;
  // The frame as one padded plane per pixel phase over the lenslets.
  PaddedPlanes in(s.lensletsX, s.lensletsY, s.psf->reach, std::size_t(pixels));
  parallelFor(0, pixels, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const int u = int(c) % n, v = int(c) / n;
      for (int t = 0; t < s.lensletsY; ++t) {
        const float* row = frame.row(t * n + v, 0) + u;
        float* out = in.at(c, 0, t);
        for (int x = 0; x < s.lensletsX; ++x) out[x] = row[std::size_t(x) * n];
      }
    }
  });
  Volume volume = emptyVolume();
  const std::size_t tiles = std::size_t(in.tilesX) * in.tilesY;
  // Each tile first copies the frame's planes around it: the splats of a voxel phase read any of
  // them, which from the whole planes would miss the cache at every splat.
  const int reach = in.reach, side = kTile + 2 * reach;
  const std::size_t planeSize = std::size_t(side) * side;
  parallelFor(0, tiles, 1, [&](std::size_t begin, std::size_t end) {
    float sums[kTileSize];
    std::vector<float> local(planeSize * pixels);
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int x0 = int(tile % in.tilesX) * kTile, y0 = int(tile / in.tilesX) * kTile;
      for (int c = 0; c < pixels; ++c)
        for (int r = 0; r < side; ++r) {
          const float* row = in.at(c, x0 - reach, y0 - reach + r);
          std::copy(row, row + side, local.data() + c * planeSize + std::size_t(r) * side);
        }
      const float* origin = local.data() + std::size_t(reach) * side + reach;
      for (std::size_t p = 0; p < s.phases(); ++p) {
        const int z = int(p / (k * k)), j = int(p / k % k), i = int(p % k);
        const auto splats = s.psf->of(z, i, j);
        backwardPhase(sums, origin, planeSize, side, splats.data(), splats.data() + splats.size());
        for (int r = 0; r < kTile && y0 + r < s.lensletsY; ++r)
          for (int x = 0; x < kTile && x0 + x < s.lensletsX; ++x)
            volume.at((x0 + x) * k + i, (y0 + r) * k + j, z) = sums[r * kTile + x];
      }
    }
  });
  return volume;
}

}  // namespace lfcam
