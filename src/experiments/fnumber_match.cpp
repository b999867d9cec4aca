// Figure 2: the main lens's image-side f-number against the microlenses' (f/4). Raw close-ups
// of a white field at f/2.8, f/4 and f/8, and the diameter of one microlens's image measured
// against the pitch: larger than the pitch (overlap, cross-talk), equal, or smaller (wasted pixels).
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/simulate/simulate.hpp"

namespace lfcam::experiments {

namespace {

// Diameter of the disc with the same area as the light under one microlens: the summed
// irradiance over the brightest pixel's, so that partly lit pixels count by their share.
double equivalentDiameterPx(const Image& irradiance) {
  double sum = 0, peak = 0;
  for (float e : irradiance.pixels()) sum += e, peak = std::max(peak, double(e));
  return peak > 0 ? 2 * std::sqrt(sum / peak / 3.141592653589793) : 0;
}

}  // namespace

Status runFNumberMatch(const std::filesystem::path& folder, const ExperimentOptions& options) {
  const int n = 12, closeUp = 6, array = options.quick ? 8 : 16;
  const int samples = options.quick ? 16 : 64;
  const std::vector<double> stops{2.8, 4, 8};
  Report report("Matching the main lens and microlens f-numbers (Figure 2)");
  std::vector<double> measured, predicted, ratios, darkShares;
  const Scene white = whiteScene();
  double pitchPx = 0;
  std::vector<std::vector<std::string>> rows;
  for (double stop : stops) {
    CameraModel camera = plenopticCamera(array, n);
    camera.mainLens.setImageSideFNumber(stop);
    pitchPx = camera.microlenses->pitchMm *
              (1 + camera.microlenses->separationMm() / camera.mainLens.imageDistanceMm()) / camera.sensor.pixelPitchMm;
    // One microlens alone on a sensor three images wide: its whole image, whatever overlaps it.
    CameraModel single = camera;
    single.microlenses->columns = single.microlenses->rows = 1;
    single.sensor.width = single.sensor.height = 3 * n;
    SimulationOptions simulation;
    simulation.samplesPerPixel = samples;
    const double diameter = equivalentDiameterPx(simulateCapture(white, single, simulation).irradiance);
    // The array: raw close-up, and the share of pixels that no light reaches (wasted).
    const Image raw = simulateCapture(white, camera, simulation).irradiance;
    double peak = 0;
    for (float e : raw.pixels()) peak = std::max(peak, double(e));
    std::size_t dark = 0;
    for (float e : raw.pixels()) dark += e < 0.05 * peak;
    const double darkShare = double(dark) / double(raw.planeSize());
    const int size = closeUp * n, x0 = (raw.width() - size) / 2, y0 = (raw.height() - size) / 2;
    Image crop(size, size, 1);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) crop.at(x, y, 0) = raw.at(x0 + x, y0 + y, 0);
    const std::string name = fixed(stop, 1);
    report.image("raw_f" + name + ".png", forDisplay(crop, 4, peak),
                 "Raw close-up of a white field, main lens at f/" + name);
    measured.push_back(diameter);
    predicted.push_back(camera.microlensImageDiameterPx());
    ratios.push_back(diameter / pitchPx);
    darkShares.push_back(darkShare);
    rows.push_back({"f/" + name, fixed(diameter, 2), fixed(camera.microlensImageDiameterPx(), 2), fixed(pitchPx, 2),
                    fixed(diameter / pitchPx, 3), fixed(100 * darkShare, 1),
                    diameter > 1.02 * pitchPx  ? "overlap"
                    : diameter < 0.9 * pitchPx ? "too small"
                                               : "matched"});
    if (options.progress) options.progress(double(rows.size()) / stops.size());
  }
  // The widest aperture whose images do not overlap.
  double matched = stops.back();
  for (std::size_t i = 0; i < stops.size(); ++i)
    if (ratios[i] <= 1.02) {
      matched = stops[i];
      break;
    }
  report.heading("Setup");
  report.paragraph(
      "Microlenses of 125 um at f/4 (the paper's), " + std::to_string(n) +
      " pixels per microlens image pitch, the main lens stopped to image-side f/2.8, f/4 and f/8, a white field. " +
      "Diameter: the disc with the area of the light of one microlens traced alone (summed irradiance over the " +
      "brightest pixel's), against the pitch of the microlens images on the sensor. Dark pixels: under 5% of the " +
      "brightest in the whole array.");
  report.heading("Results");
  report.table("diameters.csv",
               {"main lens", "image diameter (px)", "predicted (px)", "pitch (px)", "diameter / pitch",
                "dark pixels (%)", "verdict"},
               rows);
  Plot plot{"Microlens image diameter against f-number", "image-side f-number", "diameter / pitch", true, {}, {}, {}};
  plot.series.push_back({"measured", stops, ratios, true, true, false});
  std::vector<double> predictedRatio;
  for (double p : predicted) predictedRatio.push_back(p / pitchPx);
  plot.series.push_back({"aperture x separation / F", stops, predictedRatio, true, false, false});
  plot.horizontalLines.push_back({"pitch", 1.0});
  report.plot("diameter.svg", plot, "Diameter of a microlens image over the pitch: above 1 the images overlap.");
  report.heading("Against the paper");
  report.paragraph(
      "The paper: at f/4 the images are as large as possible without overlapping; at f/2.8 they overlap, at f/8 "
      "they are too small and pixels are wasted. Here the widest stop without overlap is f/" +
      fixed(matched, 1) + ".");
  auto& r = report.results();
  r["experiment"] = "fnumber-match";
  r["quick"] = options.quick;
  r["f_numbers"] = stops;
  r["diameter_px"] = measured;
  r["predicted_diameter_px"] = predicted;
  r["pitch_px"] = pitchPx;
  r["diameter_over_pitch"] = ratios;
  r["dark_pixel_share"] = darkShares;
  r["matched_f_number"] = matched;
  r["paper_matched_f_number"] = 4;
  return report.write(folder);
}

}  // namespace lfcam::experiments
