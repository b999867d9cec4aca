// Occlusion edges of a disparity map (edof_internal.hpp): the background beside a nearer surface
// given back to the background.
//
// Why: where the background has little texture, no subset of views tells its disparity from the
// nearer surface's (both make the views agree), so the aggregation and the optimisation carry the
// nearer disparity a few pixels onto the background ("fattening"; on HCI antinous background
// pixels 1, 2, 3 px beside a nearer surface were 88, 73, 53 % bad). Only the centre view's
// colours can tell which surface a pixel belongs to. Pixels near a jump of the map are the
// unsure ones; those further away vote, weighted by colour likeness, and a pixel moves to the
// farther surface when that surface's voters outweigh its own: the nearer surface does not
// extend past its own colour edge. Only moves to a farther surface: a nearer surface's own edge
// pixels, textured, keep what the cost said (allowing both ways made the layered planes' MSE
// worse, 8.1 -> 11.7, measured with a jump of 0.3 and voter radius 6). The voters' disparities
// are carried to the pixel along their surface's slope (mapSlopes), then counted as its own
// surface or a farther one: a floor seen behind a statue changes by up to 0.4 px across the
// voters' window (carried: development means 1.96 -> 1.93 % at 128 px per view, 3.36 -> 3.30 % at
// 256; also counted by the carried value, with the jump at 0.3: 1.84 -> 1.81 % and 3.07 -> 3.05 %).
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/parallel.hpp"
#include "edof/edof_internal.hpp"

namespace lfcam::edof {

namespace {

// Disparity difference between 4-neighbours that counts as an occlusion jump, px per view step
// (a floor slanted by 0.075 per row is far from it); also the largest difference from the pixel of
// a voter of its own surface, once carried along that surface's slope. Chosen on the development
// scenes with the voters carried and classified so: 0.25, 0.3, 0.4, 0.5 gave means of 1.78, 1.81,
// 1.90, 1.86 % at 128 px per view and 3.06, 3.05, 3.25, 3.23 % at 256 (at 0.25 the noisy thin
// bars 5.74 % at 256).
constexpr float kJump = 0.3f;
// Voters come from a (2 kVoterRadius + 1)^2 window; colour likeness exp(-c^2 / (2 kSigma^2)), c
// the Euclidean distance of sRGB colours.
constexpr int kVoterRadius = 10;
constexpr float kSigma = 0.05f;
// The farther surface must gather at least the vote of one voter of its very colour: a structure
// thinner than the band (a bar, a rail) has no voters of its own, and without this floor the
// faint likeness of voters of another colour took it (thin bars 12.0 -> 9.8 % BadPix(0.07)).
constexpr float kMinimumVotes = 1.0f;

}  // namespace

std::vector<int> jumpDistance(const float* disparity, int width, int height, float jump, int cap) {
  const std::size_t n = std::size_t(width) * height;
  std::vector<int> distance(n, cap + 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = std::size_t(y) * width + x;
      if (x + 1 < width && std::abs(disparity[p + 1] - disparity[p]) > jump) distance[p] = distance[p + 1] = 0;
      if (y + 1 < height && std::abs(disparity[p + width] - disparity[p]) > jump) distance[p] = distance[p + width] = 0;
    }
  // Two raster passes over the 8-neighbourhood give the chessboard distance exactly.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int& d = distance[std::size_t(y) * width + x];
      if (x > 0) d = std::min(d, distance[std::size_t(y) * width + x - 1] + 1);
      if (y > 0)
        for (int dx = std::max(x - 1, 0); dx <= std::min(x + 1, width - 1); ++dx)
          d = std::min(d, distance[std::size_t(y - 1) * width + dx] + 1);
    }
  for (int y = height - 1; y >= 0; --y)
    for (int x = width - 1; x >= 0; --x) {
      int& d = distance[std::size_t(y) * width + x];
      if (x + 1 < width) d = std::min(d, distance[std::size_t(y) * width + x + 1] + 1);
      if (y + 1 < height)
        for (int dx = std::max(x - 1, 0); dx <= std::min(x + 1, width - 1); ++dx)
          d = std::min(d, distance[std::size_t(y + 1) * width + dx] + 1);
    }
  for (int& d : distance) d = std::min(d, cap + 1);
  return distance;
}

void reclaimOcclusionEdges(const Image& guide, int band, bool slanted, float* disparity,
                           const ReclaimCheck& costAllows) {
  const int width = guide.width(), height = guide.height(), channels = guide.channels();
  if (band <= 0 || width < 1 || height < 1) return;
  const std::vector<int> distance = jumpDistance(disparity, width, height, kJump, band);
  const std::vector<float> input(disparity, disparity + std::size_t(width) * height);
  const MapSlopes slopes = slanted ? mapSlopes(input.data(), width, height) : MapSlopes{};
  auto likeness = [&](std::size_t p, std::size_t q) {
    float squares = 0;
    for (int c = 0; c < channels; ++c) {
      const float difference = guide.plane(c)[p] - guide.plane(c)[q];
      squares += difference * difference;
    }
    return std::exp(-squares / (2 * kSigma * kSigma));
  };
  parallelFor(0, std::size_t(height), 4, [&](std::size_t begin, std::size_t end) {
    constexpr std::size_t kVoters = (2 * kVoterRadius + 1) * (2 * kVoterRadius + 1);
    std::vector<float> farther(kVoters + kMedianPadding), fartherWeights(kVoters + kMedianPadding);
    for (std::size_t y = begin; y < end; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = y * width + x;
        if (distance[p] > band) continue;
        float own = 0, fartherWeight = 0;
        int ownVoters = 0;
        std::size_t fartherVoters = 0;
        for (long yy = std::max(long(y) - kVoterRadius, 0L); yy <= std::min(long(y) + kVoterRadius, long(height) - 1);
             ++yy)
          for (int xx = std::max(x - kVoterRadius, 0); xx <= std::min(x + kVoterRadius, width - 1); ++xx) {
            const std::size_t q = std::size_t(yy) * width + xx;
            if (distance[q] <= band) continue;  // unsure itself: no vote
            // The voter's disparity where p is: along its surface's slope.
            const float carried =
                slanted ? input[q] + slopes.x[q] * float(x - xx) + slopes.y[q] * float(long(y) - yy) : input[q];
            if (std::abs(carried - input[p]) <= kJump) {
              own += likeness(p, q);
              ++ownVoters;
            } else if (carried < input[p] - kJump) {
              const float weight = likeness(p, q);
              fartherWeight += weight;
              farther[fartherVoters] = carried;
              fartherWeights[fartherVoters++] = weight;
            }
          }
        if (fartherWeight > own && fartherWeight > kMinimumVotes) {
          const float to = weightedMedianSelect(farther.data(), fartherWeights.data(), fartherVoters, fartherWeight);
          if (!costAllows || costAllows(p, input[p], to, ownVoters)) disparity[p] = to;
        }
      }
  });
}

}  // namespace lfcam::edof
