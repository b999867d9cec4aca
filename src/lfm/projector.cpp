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

// out[r] += the sum over splats of weight times a row of plane `splat.pixel` of `local` (planes
// planeSize floats apart, rows `stride` apart), offset by the splat's (dx, dy): both projections'
// inner step, one tile of sums held in registers over a list of splats. The back projection reads
// the frame's planes at L + d; the forward one the volume's at L - d (its splats negated).
LFCAM_CLONES void gatherTile(float* __restrict out, const float* __restrict local, std::size_t planeSize, int stride,
                             const LfmSplat* splat, const LfmSplat* end) {
  Row acc[kTile];
  std::memcpy(acc, out, sizeof acc);
  for (; splat != end; ++splat) {
    const float* in = local + splat->pixel * planeSize + splat->dy * stride + splat->dx;
    for (int r = 0; r < kTile; ++r) {
      Row row;
      std::memcpy(&row, in + r * stride, sizeof row);
      acc[r] += splat->weight * row;
    }
  }
  std::memcpy(out, acc, sizeof acc);
}

// Copies the padded planes [first, first + count) of `in` around the tile at (x0, y0) into
// `local`, each (kTile + 2 reach)^2 floats: the splats then read from cache, not the whole planes.
void copyAroundTile(const PaddedPlanes& in, std::size_t first, std::size_t count, int x0, int y0, float* local) {
  const int side = kTile + 2 * in.reach;
  for (std::size_t c = 0; c < count; ++c)
    for (int r = 0; r < side; ++r) {
      const float* row = in.at(first + c, x0 - in.reach, y0 - in.reach + r);
      std::copy(row, row + side, local + (c * side + r) * side);
    }
}

}  // namespace

// The planes are over the array's periods (lenslets; pairs of lenslet rows of a hexagonal array),
// a period holding n x rows n pixels and k x rows k voxels.
struct LfmProjector::State {
  const LfmSparsePsf* psf = nullptr;
  int lensletsX = 0, lensletsY = 0;
  int n = 0, k = 0, rows = 1, slices = 0;
  // The splats turned around for the forward projection: per (slice, pixel), the voxel phases
  // (j K + i, in `pixel`) lighting that pixel, their offsets negated.
  std::vector<std::size_t> byPixelBegins;
  std::vector<LfmSplat> byPixel;

  int periodsY() const { return lensletsY / rows; }
  int pixelRows() const { return rows * n; }  // of a period
  int voxelRows() const { return rows * k; }
  std::size_t phasesPerSlice() const { return std::size_t(k) * voxelRows(); }
  std::size_t phases() const { return slices * phasesPerSlice(); }
};

LfmProjector::LfmProjector(const LfmSparsePsf& psf, int lensletsX, int lensletsY)
    : state_(std::make_unique<State>(State{.psf = &psf,
                                           .lensletsX = lensletsX,
                                           .lensletsY = lensletsY,
                                           .n = psf.grid.pixelsPerLenslet,
                                           .k = psf.grid.voxelsPerLenslet,
                                           .rows = psf.optics.rowsPerPeriod(),
                                           .slices = int(psf.grid.depthsUm.size())})) {
  State& s = *state_;
  const std::size_t pixels = std::size_t(s.n) * s.pixelRows(), phasesPerSlice = s.phasesPerSlice();
  // A counting sort of every slice's splats by pixel.
  s.byPixelBegins.assign(s.slices * pixels + 1, 0);
  for (int z = 0; z < s.slices; ++z)
    for (std::size_t a = 0; a < phasesPerSlice; ++a)
      for (const LfmSplat& splat : psf.of(z, int(a % s.k), int(a / s.k)))
        ++s.byPixelBegins[z * pixels + splat.pixel + 1];
  for (std::size_t i = 1; i < s.byPixelBegins.size(); ++i) s.byPixelBegins[i] += s.byPixelBegins[i - 1];
  s.byPixel.resize(s.byPixelBegins.back());
  std::vector<std::size_t> next(s.byPixelBegins.begin(), s.byPixelBegins.end() - 1);
  for (int z = 0; z < s.slices; ++z)
    for (std::size_t a = 0; a < phasesPerSlice; ++a)
      for (const LfmSplat& splat : psf.of(z, int(a % s.k), int(a / s.k)))
        s.byPixel[next[z * pixels + splat.pixel]++] = {.pixel = std::uint16_t(a),
                                                       .dx = std::int8_t(-splat.dx),
                                                       .dy = std::int8_t(-splat.dy),
                                                       .weight = splat.weight};
}
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
  volume.voxelHeightUm = s.psf->optics.rowPitchUm() / (s.psf->optics.magnification * s.k);
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
      const int z = int(p / s.phasesPerSlice()), j = int(p / k % s.voxelRows()), i = int(p % k);
      std::fill(byOffset.begin(), byOffset.end(), 0.0);
      for (const LfmSplat& splat : s.psf->of(z, i, j))
        byOffset[std::size_t(splat.dy + reach) * side + splat.dx + reach] += splat.weight;
      // Period L reaches L + d when that lies on the frame, along x and along y apart.
      for (int x = 0; x < s.lensletsX; ++x)
        for (int dy = 0; dy < side; ++dy) {
          double sum = 0;
          for (int dx = 0; dx < side; ++dx)
            if (x + dx - reach >= 0 && x + dx - reach < s.lensletsX) sum += byOffset[std::size_t(dy) * side + dx];
          byRow[std::size_t(x) * side + dy] = sum;
        }
      for (int y = 0; y < s.periodsY(); ++y)
        for (int x = 0; x < s.lensletsX; ++x) {
          double sum = 0;
          for (int dy = 0; dy < side; ++dy)
            if (y + dy - reach >= 0 && y + dy - reach < s.periodsY()) sum += byRow[std::size_t(x) * side + dy];
          volume.at(x * k + i, y * s.voxelRows() + j, z) = float(sum);
        }
    }
  });
  return volume;
}

Image LfmProjector::forward(const Volume& volume) const {
  const State& s = *state_;
  const int k = s.k, n = s.n;
  // The volume as one padded plane per (slice, voxel phase) over the periods.
  PaddedPlanes in(s.lensletsX, s.periodsY(), s.psf->reach, s.phases());
  parallelFor(0, s.phases(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) {
      const int z = int(p / s.phasesPerSlice()), j = int(p / k % s.voxelRows()), i = int(p % k);
      for (int t = 0; t < s.periodsY(); ++t) {
        const float* row = volume.slice(z) + std::size_t(t * s.voxelRows() + j) * volume.width() + i;
        float* out = in.at(p, 0, t);
        for (int x = 0; x < s.lensletsX; ++x) out[x] = row[std::size_t(x) * k];
      }
    }
  });
  Image frame(s.lensletsX * n, s.lensletsY * n, 1);
  const int pixels = n * s.pixelRows();
  const std::size_t tiles = std::size_t(in.tilesX) * in.tilesY, phasesPerSlice = s.phasesPerSlice();
  const int side = kTile + 2 * in.reach;
  const std::size_t planeSize = std::size_t(side) * side;
  parallelFor(0, tiles, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<float> sums(std::size_t(pixels) * kTileSize), local(planeSize * phasesPerSlice);
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int x0 = int(tile % in.tilesX) * kTile, y0 = int(tile / in.tilesX) * kTile;
      std::fill(sums.begin(), sums.end(), 0.0f);
      // Slice by slice: one slice's voxel phases around the tile fit in the cache, all of them not.
      for (int z = 0; z < s.slices; ++z) {
        copyAroundTile(in, z * phasesPerSlice, phasesPerSlice, x0, y0, local.data());
        const float* origin = local.data() + std::size_t(in.reach) * side + in.reach;
        for (int c = 0; c < pixels; ++c) {
          const std::size_t list = std::size_t(z) * pixels + c;
          gatherTile(sums.data() + std::size_t(c) * kTileSize, origin, planeSize, side,
                     s.byPixel.data() + s.byPixelBegins[list], s.byPixel.data() + s.byPixelBegins[list + 1]);
        }
      }
      for (int c = 0; c < pixels; ++c) {
        const int u = c % n, v = c / n;
        for (int r = 0; r < kTile && y0 + r < s.periodsY(); ++r)
          for (int x = 0; x < kTile && x0 + x < s.lensletsX; ++x)
            frame.at((x0 + x) * n + u, (y0 + r) * s.pixelRows() + v, 0) =
                sums[std::size_t(c) * kTileSize + r * kTile + x];
      }
    }
  });
  return frame;
}

Volume LfmProjector::backward(const Image& frame) const {
  const State& s = *state_;
  const int k = s.k, n = s.n, pixels = n * s.pixelRows();
  // The frame as one padded plane per pixel phase over the periods.
  PaddedPlanes in(s.lensletsX, s.periodsY(), s.psf->reach, std::size_t(pixels));
  parallelFor(0, pixels, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      const int u = int(c) % n, v = int(c) / n;
      for (int t = 0; t < s.periodsY(); ++t) {
        const float* row = frame.row(t * s.pixelRows() + v, 0) + u;
        float* out = in.at(c, 0, t);
        for (int x = 0; x < s.lensletsX; ++x) out[x] = row[std::size_t(x) * n];
      }
    }
  });
  Volume volume = emptyVolume();
  const std::size_t tiles = std::size_t(in.tilesX) * in.tilesY;
  const int side = kTile + 2 * in.reach;
  const std::size_t planeSize = std::size_t(side) * side;
  parallelFor(0, tiles, 1, [&](std::size_t begin, std::size_t end) {
    float sums[kTileSize];
    std::vector<float> local(planeSize * pixels);
    for (std::size_t tile = begin; tile < end; ++tile) {
      const int x0 = int(tile % in.tilesX) * kTile, y0 = int(tile / in.tilesX) * kTile;
      // Any splat of a voxel phase may read any pixel's plane.
      copyAroundTile(in, 0, pixels, x0, y0, local.data());
      const float* origin = local.data() + std::size_t(in.reach) * side + in.reach;
      for (std::size_t p = 0; p < s.phases(); ++p) {
        const int z = int(p / s.phasesPerSlice()), j = int(p / k % s.voxelRows()), i = int(p % k);
        const auto splats = s.psf->of(z, i, j);
        std::fill(std::begin(sums), std::end(sums), 0.0f);
        gatherTile(sums, origin, planeSize, side, splats.data(), splats.data() + splats.size());
        for (int r = 0; r < kTile && y0 + r < s.periodsY(); ++r)
          for (int x = 0; x < kTile && x0 + x < s.lensletsX; ++x)
            volume.at((x0 + x) * k + i, (y0 + r) * s.voxelRows() + j, z) = sums[r * kTile + x];
      }
    }
  });
  return volume;
}

}  // namespace lfcam
