// Which of the two numbers in PREFIX_AA_BB.png names the column: decided from the pictures.
// Exporters disagree (lfcam writes the row first; the LF Toolbox export of the Lytro set in the
// shared data writes the column first), and a light field read with its axes swapped refocuses
// wrongly. Parallax tells them apart: views along a row of the aperture differ by horizontal
// shifts, views along a column by vertical ones.
#pragma once

#include "io/view_folder.hpp"
#include "lfcam/core/image.hpp"

namespace lfcam::io {

// How much better a horizontal shift than a vertical one explains the difference between two
// views of one scene: > 0 when they are displaced horizontally, < 0 vertically, near 0 when
// neither (no parallax or no texture). Relative to the unshifted difference, in [-1, 1].
double horizontalParallaxEvidence(const Image& a, const Image& b);

// For a grid placed row-first, reads four views and answers ColumnFirst when the parallax says
// the numbers are the other way round, RowFirst otherwise (also when it cannot tell).
Result<ViewNumberOrder> detectViewNumberOrder(const ViewGrid& rowFirstGrid);

}  // namespace lfcam::io
