// The vocabulary of a sensor's layout, shared by the simulator, raw files and the decoder: the
// colour filter array over the photosites and the packing of the microlens lattice.
#pragma once

namespace lfcam {

enum class Packing { Square, Hexagonal };
const char* packingName(Packing packing);

enum class ColorFilter { RGGB, BGGR, GRBG, GBRG, Mono };
const char* colorFilterName(ColorFilter filter);

// Colour (0 red, 1 green, 2 blue, -1 none: monochrome) of sensor pixel (x, y).
int colorFilterChannel(ColorFilter filter, int x, int y);

}  // namespace lfcam
