// The cards of the simulator's `people` scene (scene.hpp) as a camera sees them: each card's
// disparity and the pixels well inside it, where a measurement is about that card alone. Shared by
// the people tests and bench/denoise_bench.cpp.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "lfcam/edof/depth.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"

namespace lfcam::test {

struct Card {
  std::string name;
  double disparity = 0;
  std::vector<std::size_t> interior;  // pixels (y * width + x) whose 9x9 neighbourhood all sees this card
};

// `depth`: idealDepth(scene, camera), in the (s, t) layout of the camera's light fields.
inline std::vector<Card> sceneCards(const Scene& scene, const Image& depth, const Optics& optics) {
  const int w = depth.width(), h = depth.height(), margin = 4;
  std::vector<Card> cards;
  for (const Plane& plane : scene.planes) {
    Card card{plane.name, *disparityFromDistance(optics, plane.centreMm[2]), {}};
    auto onCard = [&](int x, int y) { return std::abs(depth.at(x, y, 0) - plane.centreMm[2]) < 1e-3; };
    for (int y = margin + 1; y < h - margin - 1; ++y)
      for (int x = margin + 1; x < w - margin - 1; ++x) {
        bool inside = true;
        for (int dy = -margin; dy <= margin && inside; ++dy)
          for (int dx = -margin; dx <= margin && inside; ++dx) inside = onCard(x + dx, y + dy);
        if (inside) card.interior.push_back(std::size_t(y) * w + x);
      }
    cards.push_back(std::move(card));
  }
  return cards;
}

}  // namespace lfcam::test
