// Virtual depth from a focused plenoptic image, per pixel of a photograph's frame (photo_frame.hpp)
// and per micro-image.
//
// A point Q at virtual depth v is seen by every micro-image centred within v r of it (r the
// usable radius), at S = C + orientation (Q - C) / v (focused_calibration.hpp): neighbouring
// micro-images D pixels apart see it D / v apart, along every baseline of the lattice at once. For
// each candidate v (labels evenly spaced in that disparity D / v) the cost of a pixel is how much
// the micro-images that see it disagree (the weighted variance of their samples, luminance), over
// a small window; the map takes the least cost, refined to a fraction of a label by a parabola.
// The search goes coarse to fine over frames of half the pixels per lens in turn (down to 1): the
// coarsest costs every other label (every label when it is the map's own frame); each finer one
// only the labels within two (one, after a frame that costed every label) of the least and the
// greatest found around a pixel, and none where those agree within one label, having costed every
// label (their labels interpolated stand): it searches at depth edges, on their two sides.
// Confidence: 1 - the least cost over the greatest (how much worse the other labels are, the
// coarser frame's greatest standing for labels not costed); pixels below `minConfidence` are
// filled from confident neighbours. With fewer than two micro-images seeing a point there is no
// evidence: labels whose disc reaches fewer are not candidates.
#pragma once

#include <vector>

#include "lfcam/core/image.hpp"
#include "lfcam/core/result.hpp"
#include "lfcam/focused/focused_calibration.hpp"

namespace lfcam {

struct FocusedDepthRequest {
  double pixelsPerLens = 8;    // the map's frame
  double minVirtualDepth = 2;  // the candidates' range
  double maxVirtualDepth = 12;
  double disparityStepPx = 0.25;  // between candidates, in image pixels of D / v
  int windowRadius = 2;           // the cost's window, photograph pixels
  double minConfidence = 0.1;
};

struct FocusedDepth {
  Image virtualDepth;  // one channel on the frame
  Image confidence;    // [0, 1]
  // Per micro-image (grid.columns x grid.rows, row-major): the median virtual depth of the pixels
  // it sees nearest its centre (0 where none).
  std::vector<float> lensVirtualDepth;
};

// `image` in linear light, calibration.imageWidth x imageHeight, any number of channels.
Result<FocusedDepth> estimateFocusedDepth(const Image& image, const FocusedCalibration& calibration,
                                          const FocusedDepthRequest& request);

}  // namespace lfcam
