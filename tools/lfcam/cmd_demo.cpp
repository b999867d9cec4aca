// lfcam demo [-o DIR]: the main job on the built-in default. The page opens with a living picture
// to click (focus, aperture, viewpoint) of a real light field, the Lytro flower of ../shared/data
// (or $LFCAM_DATA_DIR) when it is there, else of the layered planes; then a light field made on
// the spot (the layered-planes scene) and everything lfcam does with it, and the camera chain from
// a simulated raw to photographs, all written to DIR with an index.html that shows it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "lfcam/calibrate/calibrate.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/io/color_map.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/raw_io/raw_io.hpp"
#include "lfcam/render/contact_sheet.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/simulate/scene.hpp"
#include "lfcam/simulate/simulate.hpp"
#include "lfcam/synth/layered_planes.hpp"
#include "lfcam/viewer/living_picture.hpp"
#include "progress_bar.hpp"
#include "raw_input.hpp"

namespace lfcam::cli {

namespace {

namespace fs = std::filesystem;

// Photographs next to each other, `gap` pixels apart on a dark background.
Image sideBySide(const std::vector<const Image*>& images, int gap) {
  int width = gap * int(images.size() - 1), height = 0;
  for (const Image* image : images) width += image->width(), height = std::max(height, image->height());
  Image row(width, height, images.front()->channels());
  std::fill(row.pixels().begin(), row.pixels().end(), 0.01f);
  int x0 = 0;
  for (const Image* image : images) {
    for (int c = 0; c < row.channels(); ++c)
      for (int y = 0; y < image->height(); ++y) std::copy_n(image->row(y, c), image->width(), row.row(y, c) + x0);
    x0 += image->width() + gap;
  }
  return row;
}

std::string slopeName(double slope) {
  char name[64];
  std::snprintf(name, sizeof name, "refocus-slope%+.2f.png", slope);
  return name;
}

Status writeText(const fs::path& path, const std::string& text) {
  return writeFileAtomically(path, [&](const fs::path& temporary) -> Status {
    std::ofstream out(temporary);
    out << text;
    out.close();
    if (!out) return makeError(ErrorCode::Io, path.string() + ": cannot write");
    return {};
  });
}

// The camera: slopes at which the simulated capture is refocused.
const std::vector<double> kCameraSlopes = {0.3, 0.0, -0.3};

std::string cameraSlopeName(double slope) { return "camera/" + slopeName(slope); }

// The middle of the raw sensor image, brightened for people: the microlens images (Figure 13).
Image rawCloseUp(const Image& raw, int size) {
  const int x0 = std::max(0, (raw.width() - size) / 2), y0 = std::max(0, (raw.height() - size) / 2);
  const int w = std::min(size, raw.width()), h = std::min(size, raw.height());
  Image crop(w, h, 1);
  float brightest = 1e-6f;
  for (float value : raw.pixels()) brightest = std::max(brightest, value);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) crop.at(x, y, 0) = raw.at(x0 + x, y0 + y, 0) / brightest;
  return crop;
}

// The paper's whole chain: a built-in scene captured by the simulated plenoptic camera (the
// prototype at reduced resolution) as a raw mosaic and a white image, the microlens grid
// calibrated from the white image, the raw decoded into a light field, and that light field
// refocused. The ideal light field is kept beside it for comparison, not used.
Status captureWithTheCamera(const fs::path& out) {
  const CameraModel camera = CameraModel::paperPrototype(1400, 1400);
  LFCAM_ASSIGN_OR_RETURN(auto scene, builtinScene("people", camera));
  const fs::path folder = out / "camera";
  {
    ProgressBar bar("simulating the camera");
    LFCAM_TRY(writeSimulation(folder, scene, camera, {}, {}, [&](double f) { bar(f); }));
  }
  LFCAM_ASSIGN_OR_RETURN(auto raw, readImage(folder / "raw.png"));
  LFCAM_TRY(writeImage(folder / "raw-closeup.png", rawCloseUp(raw, 160)));
  LFCAM_ASSIGN_OR_RETURN(auto white, readRaw(folder / "white.png"));
  LFCAM_ASSIGN_OR_RETURN(auto grid, calibrateGrid(white, CalibrationOptions{}, (folder / "white.png").string()));
  LFCAM_TRY(writeGrid(folder / "grid.json", grid));
  LFCAM_ASSIGN_OR_RETURN(auto decoded, decodeRawInput({.raw = (folder / "raw.png").string(),
                                                       .white = (folder / "white.png").string(),
                                                       .grid = (folder / "grid.json").string()}));
  LFCAM_TRY(writeLightField(folder / "decoded.lf.h5", decoded));
  for (double slope : kCameraSlopes) LFCAM_TRY(writeImage(out / cameraSlopeName(slope), refocus(decoded, slope)));
  std::printf(
      "  simulated the plenoptic camera, calibrated its microlens grid (%dx%d, pitch %.3f px, fit rms %.3f px)\n"
      "  and decoded its raw image -> camera/ (raw.png, white.png, grid.json, decoded.lf.h5)\n",
      grid.columns, grid.rows, grid.pitchX, grid.fit.rmsResidualPx);
  return {};
}

// The real light field the page opens with: the Lytro flower when the shared data is there.
std::optional<LightField> realLightField(std::string& name) {
  const char* dataDir = std::getenv("LFCAM_DATA_DIR");
  const fs::path flower = fs::path(dataDir && *dataDir ? dataDir : "../shared/data") / "lytro-f01-flower";
  std::error_code error;
  if (!fs::is_directory(flower, error)) return std::nullopt;
  auto read = readLightField(flower.string());
  if (!read) return std::nullopt;
  name = "A real Lytro capture (lytro-f01-flower, " + std::to_string(read->nu()) + "&times;" +
         std::to_string(read->nv()) + " views of " + std::to_string(read->ns()) + "&times;" +
         std::to_string(read->nt()) + " pixels)";
  return std::move(*read);
}

std::string indexPage(const LightField& lf, const std::vector<double>& slopes, const std::string& livingName) {
  std::ostringstream html;
  html << R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>lfcam demo</title>
<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;background:#111;color:#ddd}
figure{display:inline-block;margin:6px}img{max-width:340px;image-rendering:auto}figcaption{font-size:90%}
.sheet img{max-width:100%}</style></head><body>
<h1>lfcam demo</h1>
<h2>Click to focus</h2>
<p>)" << livingName
       << R"(, as a living picture: click where to focus, stop the aperture down, move the viewpoint.
The same page stands alone (<a href="living.html">living.html</a>); <code>lfcam export-html INPUT -o PAGE.html</code>
makes one of any light field.</p>
<iframe id="living" src="living.html" title="living picture" style="width:100%;height:720px;border:0;background:#000"></iframe>
<h2>A light field made on the spot</h2>
<p>A light field of )"
       << lf.nu() << "&times;" << lf.nv() << " views of " << lf.ns() << "&times;" << lf.nt()
       << R"( pixels, made on the spot: textured planes at known depths (the layered-planes scene).
Below, photographs computed from it after the fact by shift-and-add refocusing (Ng et al. 2005, Equation 6),
one focused on each plane, then the ground-truth disparity and every sub-aperture view.</p>
<h2>Refocused photographs</h2>
<figure><img src="near-and-far.png" style="max-width:100%"><figcaption>the same light field focused on the nearest and on the farthest plane</figcaption></figure><br>
)";
  for (double slope : slopes)
    html << "<figure><img src=\"" << slopeName(slope) << "\"><figcaption>focused at slope " << slope
         << " px/view</figcaption></figure>\n";
  html << R"(<h2>The scene</h2>
<figure><img src="centre-view.png"><figcaption>centre sub-aperture view (pinhole, everything sharp, noisier in a real camera)</figcaption></figure>
<figure><img src="disparity.png"><figcaption>ground-truth disparity (red = near, blue = far); values in disparity.pfm</figcaption></figure>
<h2>Depth and extended depth of field, from the light field alone</h2>
<figure><img src="depth-estimate.png"><figcaption>estimated disparity (lfcam depth), same colours</figcaption></figure>
<figure><img src="all-in-focus.png"><figcaption>all in focus (lfcam edof): a focal stack composited, full-aperture light</figcaption></figure>
<h2>The plenoptic camera, simulated</h2>
<p>The scene <code>people</code> traced ray by ray through the paper's prototype (140 mm main lens at image-side f/4,
125 &micro;m microlenses of f/4, 9 &micro;m pixels) at 1400&times;1400 pixels: under each microlens, an image of the
main lens. <code>raw.png</code> and <code>white.png</code> are what <code>lfcam simulate people</code> writes; then, as in
the paper's section 5.2, <code>lfcam calibrate</code> finds the microlens grid in the white image (<code>grid.json</code>)
and <code>lfcam decode</code> turns the raw into the light field (<code>decoded.lf.h5</code>): black level, devignetting by the
white image, demosaicing, sampling at the sub-pixel microlens centres. The photographs below are computed from that
decoded light field.</p>
<figure><img src="camera/raw-closeup.png" style="width:320px;image-rendering:pixelated"><figcaption>middle of the raw sensor image</figcaption></figure>
)";
  for (double slope : kCameraSlopes)
    html << "<figure><img src=\"" << cameraSlopeName(slope)
         << "\" style=\"width:300px\"><figcaption>the decoded light field refocused at slope " << slope
         << "</figcaption></figure>\n";
  html << R"(<h2>All sub-aperture views</h2>
<div class="sheet"><img src="contact-sheet.png"></div>
<p>The light field itself: <code>lightfield.lf.h5</code> (HDF5), its views in <code>views/</code>.
Try <code>lfcam refocus lightfield.lf.h5 --slope 0.5 -o mine.png</code>.</p>
</body></html>
)";
  return html.str();
}

Status runDemo(const fs::path& dir) {
  std::printf("lfcam demo: writing to %s\n", dir.c_str());
  LayeredPlanesLightField made = [] {
    ProgressBar bar("making the light field");
    return renderLayeredPlanes(defaultLayeredPlanesScene(), [&](double f) { bar(f); });
  }();
  const LightField& lf = made.lightField;

  // One photo per plane depth, nearest first.
  std::set<double, std::greater<>> depths;
  for (const TexturedPlane& plane : defaultLayeredPlanesScene().planes) depths.insert(plane.disparity);
  const std::vector<double> slopes(depths.begin(), depths.end());

  return writeFolderAtomically(dir, [&](const fs::path& out) -> Status {
    {
      ProgressBar bar("writing light field");
      LFCAM_TRY(writeLightField(out / "lightfield.lf.h5", lf, {}, [&](double f) { bar(f); }));
      LFCAM_TRY(writeLightField(out / "views", lf, {.format = LightFieldFormat::RowColumnFolder}));
    }
    LFCAM_TRY(writeImage(out / "contact-sheet.png", contactSheet(lf)));
    LFCAM_TRY(writeImage(out / "centre-view.png", lf.subApertureImage(lf.nu() / 2, lf.nv() / 2)));
    std::vector<Image> photos;
    for (double slope : slopes) {
      photos.push_back(refocus(lf, slope));
      LFCAM_TRY(writeImage(out / slopeName(slope), photos.back()));
      std::printf("  refocused at slope %+.2f px/view -> %s\n", slope, slopeName(slope).c_str());
    }
    // The nearest and the farthest focus side by side: the picture of the README.
    LFCAM_TRY(writeImage(out / "near-and-far.png", sideBySide({&photos.front(), &photos.back()}, 8)));
    LFCAM_TRY(writeImage(out / "disparity.pfm", made.disparity));
    LFCAM_TRY(writeImage(out / "disparity.png", colorMap(made.disparity, slopes.back(), slopes.front())));
    // Range finding and extended depth of field from the light field alone.
    LFCAM_ASSIGN_OR_RETURN(auto depth, estimateDepth(lf));
    LFCAM_TRY(writeImage(out / "depth-estimate.pfm", depth.disparity));
    LFCAM_TRY(writeImage(out / "depth-estimate.png", colorMap(depth.disparity, slopes.back(), slopes.front())));
    LFCAM_ASSIGN_OR_RETURN(auto sharp, allInFocus(lf, {.disparity = &depth.disparity}));
    LFCAM_TRY(writeImage(out / "all-in-focus.png", sharp.photo));
    std::printf("  estimated depth -> depth-estimate.png, extended depth of field -> all-in-focus.png\n");
    LFCAM_TRY(captureWithTheCamera(out));
    std::string livingName = "The layered planes made below";
    const std::optional<LightField> real = realLightField(livingName);
    {
      ProgressBar bar("making the living picture");
      LFCAM_TRY(writeLivingPicture(out / "living.html", real ? *real : lf, {.title = "lfcam demo: click to focus"},
                                   [&](double f) { bar(f); }));
    }
    std::printf("  living picture of %s -> living.html\n", real ? "the Lytro flower" : "the layered planes");
    LFCAM_TRY(writeText(out / "index.html", indexPage(lf, slopes, livingName)));
    return {};
  });
}

}  // namespace

void addDemoCommand(CLI::App& app, Job& job) {
  auto output = std::make_shared<std::string>("lfcam-demo");
  CLI::App* command = app.add_subcommand("demo", "make a light field and show what lfcam does with it");
  command->add_option("-o,--output", *output, "output folder (default: lfcam-demo)");
  command->callback([output, &job] {
    job = [output]() -> Status {
      LFCAM_TRY(runDemo(*output));
      std::printf("lfcam demo: open %s/index.html\n", output->c_str());
      return {};
    };
  });
}

}  // namespace lfcam::cli
