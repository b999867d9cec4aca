// refocusFilm (slope_field_rows.hpp): the slope-field kernel at a film's slope per pixel.
#include "render/slope_field_rows.hpp"

namespace lfcam {

Image refocusFilm(const LightField& lightField, const FilmSlopes& film, const Occluders* occluders,
                  const std::vector<float>* viewWeights) {
  auto slopeAt = [&film](int x, int y) { return film.at(x, y, x + 0.5, y + 0.5); };
  if (!occluders) return refocusSlopeField(lightField, slopeAt, KeepEveryTap{}, viewWeights);
  const float* map = film.depth->plane(0);
  const int ns = lightField.ns();
  auto keep = [&](int u, int v, int row, int column, int x, int y) {
    return !occluders->hides(u, v, row, column, map[std::size_t(y) * ns + x]);
  };
  return refocusSlopeField(lightField, slopeAt, keep, viewWeights);
}

}  // namespace lfcam
