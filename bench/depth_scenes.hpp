// The development scenes of the depth estimator: light fields with their exact disparity, on
// which its defaults are chosen. HCI antinous is not among them: it is scored as a held-out check
// only (bench/depth_bench.cpp, tests/realdata/hci_depth_test.cpp), never used to choose a
// parameter.
#pragma once

#include <string>
#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/light_field.hpp"

namespace lfcam::bench {

struct DepthScene {
  std::string name;
  LightField lightField;
  Image disparity;                    // exact, ns x nt, pixels per view step
  double disparityMin, disparityMax;  // the range searched: the truth's, 0.25 wider each side
};

// `synth` layered planes (also with texture four times coarser), the simulator's people scene
// (noise-free and with Lytro-like noise), and simulator scenes built for this: a floor at a grazing
// angle, a floor and a wall whose disparity changes fast (also with weak texture, and that again
// unevenly lit and glossy), cards standing on such a floor, a curved surface (half an elliptic
// cylinder of 32 facets), a grey column bulging far towards the camera before a grey wall, thin bars
// before a wall, fine texture, weak texture (4 % contrast); the grazing floor, the surface and the
// weak texture's near card also glossy (brightness -10 % to +10 % across the aperture); the surface
// also varnished (a mirror reflectance of 0.04 rising towards grazing angles, Fresnel); narrow near
// parts (below). The simulator's: 12 x 12 views of `size` x `size` (synth: 9 x 9).
std::vector<DepthScene> developmentScenes(int size = 128);

// Narrow near parts before a far wall, as a statue's fingers and arm: strips 3 to 8 pixels wide
// (every pixel within the occlusion edges' band of 3) at a disparity jump of 1.9 px, their pale
// texture close in colour to the wall's lighter parts.
DepthScene narrowNearParts(int size = 128);

// The synth layered planes with texture four times coarser: faint evidence beside confident cards,
// the background's features wider than any window, so locally a ramp.
DepthScene coarseLayeredPlanes(int size = 128);

// A card of weak texture (4 % contrast) before a wall as weak, the card glossy (its brightness
// -10 % to +10 % across the aperture).
DepthScene weakTextureGlossy(int size = 128);

}  // namespace lfcam::bench
