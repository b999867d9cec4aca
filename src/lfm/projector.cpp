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

// out[r][x] += weight * in[r * stride + x] over one tile: the forward projection's inner step.
LFCAM_CLONES void splatTile(float* __restrict out, const float* __restrict in, int stride, float weight) {
  for (int r = 0; r < kTile; ++r)
    for (int x = 0; x < kTile; ++x) out[r * kTile + x] += weight * in[r * stride + x];
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
        for (const LfmSplat& splat : s.psf->of(z, i, j))
          splatTile(sums.data() + std::size_t(splat.pixel) * kTileSize, origin - splat.dy * in.width - splat.dx,
                    in.width, splat.weight);
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
  parallelFor(0, tiles, 1, [&](std::size_t begin, std::size_t end) {
    float sums[kTileSize];
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int x0 = int(tile % in.tilesX) * kTile, y0 = int(tile / in.tilesX) * kTile;
      for (std::size_t p = 0; p < s.phases(); ++p) {
        const int z = int(p / (k * k)), j = int(p / k % k), i = int(p % k);
        std::fill(std::begin(sums), std::end(sums), 0.0f);
        for (const LfmSplat& splat : s.psf->of(z, i, j))
          splatTile(sums, in.at(splat.pixel, x0 + splat.dx, y0 + splat.dy), in.width, splat.weight);
        for (int r = 0; r < kTile && y0 + r < s.lensletsY; ++r)
          for (int x = 0; x < kTile && x0 + x < s.lensletsX; ++x)
            volume.at((x0 + x) * k + i, (y0 + r) * k + j, z) = sums[r * kTile + x];
      }
    }
  });
  return volume;
}

}  // namespace lfcam
