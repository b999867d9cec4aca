// Photographs from Python: refocus and stack take every field of the photograph request
// (photo_request.hpp) as a keyword (its name with '_' for '-'), turned into the text the command
// line would give and parsed by the same table, so that both refuse the same requests with the same
// line; aperture_mask and depth take arrays. photo_fields() lists the table; the docstrings come
// from it.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "arrays.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "lfcam/photo/photo_request.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace py = pybind11;

namespace lfcam::python {

namespace {

std::string numberText(const py::handle& value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value.cast<double>());
  return text;
}

// A Python value as the field's text: numbers as numbers, pairs "a,b", a pair of ends "a:b" (the
// syntax says which), three points "x1,y1:x2,y2:x3,y3", a bool "true"/"false"; anything else by
// str(), which the field's parser then refuses in its own words.
std::string fieldText(const PhotoField& field, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return numberText(value);
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    const std::string syntax = field.syntax;
    const bool ends = syntax.find(':') != std::string::npos && syntax.find(',') == std::string::npos;
    bool numbers = true;
    for (const py::handle& item : value.cast<py::sequence>())
      numbers = numbers && (py::isinstance<py::int_>(item) || py::isinstance<py::float_>(item));
    std::string text;
    for (const py::handle& item : value.cast<py::sequence>())
      text += (text.empty() ? "" : numbers && !ends ? "," : ":") + fieldText(field, item);
    return text;
  }
  return py::str(value).cast<std::string>();
}

// The request the keywords describe, on top of `request`; keywords the table does not know, and
// those of groups the call does not take, are usage errors.
PhotoRequest requestFrom(const py::kwargs& keywords, const std::vector<std::string>& groups, PhotoRequest request) {
  for (const auto& [key, value] : keywords) {
    const std::string name = key.cast<std::string>();
    const PhotoField* field = findPhotoField(name);
    if (!field || std::find(groups.begin(), groups.end(), field->group) == groups.end())
      throw LibraryError(ErrorCode::Usage, "unknown keyword '" + name + "'");
    if (value.is_none()) continue;
    if (field->fromFile && py::isinstance<py::array>(value)) {
      auto image = std::make_shared<const Image>(imageFromArray(value.cast<py::array>(), field->name));
      (std::string(field->name) == "depth" ? request.depth : request.apertureMask) = std::move(image);
      continue;
    }
    throwIfError(setPhotoField(request, name, fieldText(*field, value)));
  }
  throwIfError(checkPhotoRequest(request));
  return request;
}

std::string fieldsHelp(const std::vector<std::string>& groups) {
  std::string help;
  for (const PhotoField& field : photoFields()) {
    if (std::find(groups.begin(), groups.end(), field.group) == groups.end()) continue;
    std::string name = field.name;
    std::replace(name.begin(), name.end(), '-', '_');
    help += "\n  " + name + (*field.syntax ? std::string(" (") + field.syntax + ")" : "") + ": " + field.help;
  }
  return help;
}

}  // namespace

void bindPhotos(py::module_& m) {
  const std::vector<std::string> all{"focus", "aperture", "lens", "sampling"};
  const std::vector<std::string> stackGroups{"aperture", "lens", "sampling"};
  m.def(
      "photo_fields",
      [] {
        py::list fields;
        for (const PhotoField& field : photoFields()) {
          std::string name = field.name;
          std::replace(name.begin(), name.end(), '-', '_');
          fields.append(py::dict(py::arg("name") = name, py::arg("group") = field.group,
                                 py::arg("syntax") = field.syntax, py::arg("help") = field.help));
        }
        return fields;
      },
      "The photograph request's fields: the keywords of refocus (and, but the focus and upsample, of stack), the "
      "command line's flags (--name with '-' for '_') and the viewer's query parameters.");
  m.def(
      "refocus",
      [all](const LightField& lf, const py::object& slope, const py::kwargs& keywords) {
        // The positional slope is the keyword slope, parsed alike.
        PhotoRequest start;
        if (!slope.is_none()) throwIfError(setPhotoField(start, "slope", fieldText(*findPhotoField("slope"), slope)));
        const PhotoRequest request = requestFrom(keywords, all, start);
        return interruptible([&] { return valueOrThrow(renderPhoto(lf, request)); });
      },
      py::arg("light_field"), py::arg("slope") = py::none(),
      ("A photograph of Equation 5: give the focus (one of slope, alpha, focus_at, focus_plane, focus_range), and "
       "optionally the aperture, the lens plane and the sampling, in any combination. Keywords:" +
       fieldsHelp(all))
          .c_str());
  m.def(
      "stack",
      [stackGroups](const LightField& lf, std::optional<std::vector<double>> slopes,
                    std::optional<std::vector<double>> alphas, const py::kwargs& keywords) {
        if (slopes.has_value() == alphas.has_value())
          throw LibraryError(ErrorCode::Usage, "stack: give the depths with one of slopes or alphas");
        if (keywords.contains("upsample")) throw LibraryError(ErrorCode::Usage, "unknown keyword 'upsample'");
        PhotoRequest start;
        start.slope = 0.0;  // each slice sets its own
        const PhotoRequest request = requestFrom(keywords, stackGroups, start);
        std::vector<double> values = slopes ? *slopes : *alphas;
        if (alphas)
          for (double& value : values) value = valueOrThrow(slopeFromAlpha(lf, value, "light field"));
        std::vector<Image> photos;
        interruptible([&] {
          const ResolvedPhoto photo = valueOrThrow(resolvePhoto(request, lf));
          throwIfError(renderPhotos(lf, photo, values, [&](int, double, Image&& image) -> Status {
            if (cancellationRequested()) return makeError(ErrorCode::Usage, "cancelled");  // no more photographs
            photos.push_back(std::move(image));
            return {};
          }));
        });
        return photos;
      },
      py::arg("light_field"), py::arg("slopes") = py::none(), py::kw_only(), py::arg("alphas") = py::none(),
      ("A focal stack: one photograph per slope (or alpha), through the same aperture. Keywords:" +
       fieldsHelp(stackGroups))
          .c_str());
  m.def(
      "observer",
      [](const LightField& lf, double u, double v, double beta, bool clamp) {
        const PhotoRequest request{
            .slope = 0.0, .aperture = 0.0, .apertureCentre = std::array<double, 2>{u, v}, .clamp = clamp, .beta = beta};
        return interruptible([&] { return valueOrThrow(renderPhoto(lf, request)); });
      },
      py::arg("light_field"), py::arg("u"), py::arg("v"), py::kw_only(), py::arg("beta") = 1.0,
      py::arg("clamp") = false,
      "The view of a pinhole at (u, v) view steps from the centre, moved along the axis by beta (Equation 7): "
      "refocus(light_field, 0, aperture=0, aperture_centre=(u, v), beta=beta, clamp=clamp).");
}

}  // namespace lfcam::python
