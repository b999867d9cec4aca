// LightField: the 4D light field L(u, v, s, t) of the paper (section 3.3), with colour channels
// and an optional per-sample weight.
//
// Coordinates, in the paper's names:
//   (u, v)  position on the main-lens aperture: the angular axes. Each (u, v) is one
//           sub-aperture view. Indices u in [0, nu), v in [0, nv). The centre of the aperture is
//           at index ((nu - 1) / 2, (nv - 1) / 2), a half-integer when nu or nv is even (the
//           centre then lies between views). u grows with the view's column and v with its row
//           when the views are laid out as seen from behind the camera: u to the right, v down,
//           the same directions as s and t.
//   (s, t)  position on the microlens plane: the spatial axes, in pixels of a sub-aperture
//           image. s grows to the right, t downwards; pixel centres at (s + 0.5, t + 0.5) as in
//           image.hpp.
// Units: on the command line and in render functions, (u, v) are counted in view steps from the
//   centre, (s, t) in pixels, and disparity ("slope") in pixels of (s, t) per view step. A
//   surface of disparity d appears in view (u, v) displaced by (-u d, -v d) relative to the
//   centre (u, v measured from the centre), which is the HCI benchmark's convention: positive d
//   is nearer than the plane in focus at capture. Light fields decoded from raws follow it too:
//   decode keeps the raw's lenslet layout as (s, t) and takes view u from the pixel u - (nu - 1) / 2
//   right of each microlens image's centre (decode.hpp says why).
//
// Memory: one contiguous float32 buffer (on huge pages when large and asked for:
// huge_page_allocator.hpp), views outermost:
//   index(u, v, s, t, c) = (((v * nu + u) * channels + c) * nt + t) * ns + s
// so each (view, channel) is a row-major image plane, which a refocus streams through whole.
// The weight (when present) has one plane per view: weightIndex(u, v, s, t) = ((v * nu + u) * nt
// + t) * ns + s. A weight of 1 means the sample lay fully inside the aperture / white image, 0
// means it carries no light (outside the lens, between microlenses). Sample values are already
// normalised by their weight (radiance, not collected light); the weight says how far to trust
// them.
//
// Move-only, like Image.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lfcam/core/detail/huge_page_allocator.hpp"
#include "lfcam/core/image.hpp"

namespace lfcam {

struct LightFieldShape {
  int nu = 0, nv = 0;  // angular: views across and down
  int ns = 0, nt = 0;  // spatial: pixels across and down in each view
  int channels = 0;

  std::size_t viewPixels() const { return std::size_t(ns) * std::size_t(nt); }
  std::size_t views() const { return std::size_t(nu) * std::size_t(nv); }
  std::size_t samples() const { return views() * viewPixels() * std::size_t(channels); }
  bool operator==(const LightFieldShape&) const = default;
};

// The optics behind a light field, when known: what converts the paper's alpha into a slope.
struct Optics {
  double lensStepMm = 0;                // du: spacing of adjacent views on the main-lens plane
  double spatialStepMm = 0;             // ds: spacing of adjacent (s, t) samples on the microlens plane
  double lensToMicrolensMm = 0;         // F: main lens (principal plane) to microlens plane
  std::optional<double> focalLengthMm;  // main lens, for metric distances

  // Refocusing to relative film depth alpha (Equation 6) shifts each view by this many pixels
  // per view step: slope = (du / ds) (1 - 1 / alpha). See docs/paper-notes in design.md.
  double slopeFromAlpha(double alpha) const;
  double alphaFromSlope(double slope) const;
};

struct LightFieldMetadata {
  std::optional<Optics> optics;
  // Disparity range of the scene, in pixels per view step, when the source states it (HCI).
  std::optional<double> disparityMin, disparityMax;
  std::string source;  // free text: where the light field came from
};

class LightField {
 public:
  LightField() = default;
  // Zero-filled samples; no weight until enableWeight(). `pages`: Ordinary for a light field
  // that is written once and passed on (huge_page_allocator.hpp).
  explicit LightField(const LightFieldShape& shape, Pages pages = Pages::Huge);

  LightField(LightField&&) noexcept = default;
  LightField& operator=(LightField&&) noexcept = default;
  LightField(const LightField&) = delete;
  LightField& operator=(const LightField&) = delete;
  LightField copy() const;

  const LightFieldShape& shape() const { return shape_; }
  int nu() const { return shape_.nu; }
  int nv() const { return shape_.nv; }
  int ns() const { return shape_.ns; }
  int nt() const { return shape_.nt; }
  int channels() const { return shape_.channels; }
  bool empty() const { return data_.empty(); }

  // Position of view index u (or v) in view steps from the aperture centre.
  double uFromCentre(int u) const { return u - 0.5 * (shape_.nu - 1); }
  double vFromCentre(int v) const { return v - 0.5 * (shape_.nv - 1); }

  float* plane(int u, int v, int c) { return data_.data() + planeOffset(u, v, c); }
  const float* plane(int u, int v, int c) const { return data_.data() + planeOffset(u, v, c); }
  float& at(int u, int v, int s, int t, int c) { return plane(u, v, c)[std::size_t(t) * shape_.ns + s]; }
  float at(int u, int v, int s, int t, int c) const { return plane(u, v, c)[std::size_t(t) * shape_.ns + s]; }

  bool hasWeight() const { return !weight_.empty(); }
  // Adds a weight plane for every view, filled with `value`.
  void enableWeight(float value = 1.0f);
  void dropWeight() {
    weight_.clear();
    weight_.shrink_to_fit();
  }
  float* weightPlane(int u, int v) { return weight_.data() + viewIndex(u, v) * shape_.viewPixels(); }
  const float* weightPlane(int u, int v) const { return weight_.data() + viewIndex(u, v) * shape_.viewPixels(); }

  std::span<float> samples() { return data_; }
  std::span<const float> samples() const { return data_; }
  std::span<float> weights() { return weight_; }
  std::span<const float> weights() const { return weight_; }

  // The photograph through one sub-aperture (section 3.3, Figure 4): a copy of view (u, v).
  Image subApertureImage(int u, int v) const;
  // Stores `image` (ns x nt, same channels) as view (u, v).
  void setSubApertureImage(int u, int v, const Image& image);

  LightFieldMetadata metadata;

 private:
  std::size_t viewIndex(int u, int v) const { return std::size_t(v) * shape_.nu + u; }
  std::size_t planeOffset(int u, int v, int c) const {
    return (viewIndex(u, v) * shape_.channels + c) * shape_.viewPixels();
  }

  LightFieldShape shape_;
  std::vector<float, HugePageAllocator<float>> data_;
  std::vector<float, HugePageAllocator<float>> weight_;
};

}  // namespace lfcam
