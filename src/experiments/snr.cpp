// Figure 12: at the same exposure time, a conventional f/22 photograph against the refocused
// f/4 light field, noise measured against a noise-free standard averaged from many frames.
#include <algorithm>
#include <cmath>
#include <functional>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis/analysis.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace lfcam::experiments {

namespace {

double totalElectrons(const TracedCapture& traced) {
  double sum = 0;
  for (float e : traced.irradiance.pixels()) sum += e;
  return sum * traced.camera.sensor.exposure * traced.camera.sensor.electronsPerIrradiance;
}

struct Measured {
  SignalToNoise snr;
  Image standard, frame;  // the standard and one noisy frame, for display
};

// SNR of the photographs made by `photos(seed)` (one per way of making them from the same
// exposure): `standardFrames` frames averaged into the standard, `testFrames` others measured
// against it (their squared errors pooled). The standard keeps 1/standardFrames of a frame's
// noise variance; it is taken out of the measured noise.
Result<std::vector<Measured>> measure(const std::function<Result<std::vector<Image>>(std::uint64_t)>& photos,
                                      int standardFrames, int testFrames, const Image& mask) {
  std::vector<std::vector<Image>> frames;  // [way][frame]
  for (int k = 0; k < standardFrames; ++k) {
    LFCAM_ASSIGN_OR_RETURN(auto images, photos(1000 + std::uint64_t(k)));
    frames.resize(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) frames[i].push_back(std::move(images[i]));
  }
  std::vector<Measured> measured(frames.size());
  std::vector<double> variance(frames.size(), 0.0);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::vector<const Image*> pointers;
    for (const Image& f : frames[i]) pointers.push_back(&f);
    LFCAM_ASSIGN_OR_RETURN(auto standard, averageImages(pointers));
    measured[i].standard = std::move(standard);
  }
  for (int k = 0; k < testFrames; ++k) {
    LFCAM_ASSIGN_OR_RETURN(auto images, photos(1 + std::uint64_t(k)));
    for (std::size_t i = 0; i < measured.size(); ++i) {
      LFCAM_ASSIGN_OR_RETURN(auto snr, signalToNoise(images[i], measured[i].standard, &mask));
      measured[i].snr.signal = snr.signal;
      variance[i] += snr.noise * snr.noise / testFrames;
      if (k == 0) measured[i].frame = std::move(images[i]);
    }
  }
  for (std::size_t i = 0; i < measured.size(); ++i) {
    SignalToNoise& snr = measured[i].snr;
    snr.noise = std::sqrt(variance[i] * standardFrames / (standardFrames + 1));
    snr.snr = snr.noise > 0 ? snr.signal / snr.noise : 0;
  }
  return measured;
}

}  // namespace

Status runSnr(const std::filesystem::path& folder, const ExperimentOptions& options) {
  const int microlenses = options.quick ? 32 : 64, n = options.quick ? 8 : 12;
  // The blur is twice the microlens image (N pixels): in focus, the views shift by a whole 2
  // pixels per view step, so shift-and-add needs no interpolation, which would average noise.
  const double blur = 2.0 * n;
  const int samples = options.quick ? 4 : 16, standardFrames = options.quick ? 8 : 32,
            testFrames = options.quick ? 2 : 8;
  const std::vector<double> stops{4, 5.6, 8, 11, 16, 22};
  const CameraModel plenoptic = plenopticCamera(microlenses, n);
  const double target = defocusedDistanceMm(plenoptic, blur);
  const Scene chart = chartScene(plenoptic, target);

  LFCAM_ASSIGN_OR_RETURN(auto traced, traceCapture(chart, plenoptic, samples));
  // The refocus depth: where the pinhole target at the chart's distance is sharpest (section 6.1).
  LFCAM_ASSIGN_OR_RETURN(auto pinholeTraced,
                         traceCapture(pinholeScene(plenoptic, target), plenoptic, options.quick ? 16 : 64));
  LFCAM_ASSIGN_OR_RETURN(auto clean, captureLightField(pinholeTraced, false, 1));
  LFCAM_ASSIGN_OR_RETURN(auto best, refocusToSharpest(clean));
  if (options.progress) options.progress(0.3);
  // Borders, where refocusing has fewer views to add, are left out of every measurement.
  const int border = std::min(microlenses / 4, int(std::ceil(std::abs(best.slope) * 0.5 * n)) + 1);
  Image mask(microlenses, microlenses, 1);
  for (int y = border; y < microlenses - border; ++y)
    for (int x = border; x < microlenses - border; ++x) mask.at(x, y, 0) = 1;

  // The paper's measurement adds the pixels as they are: the views shifted by whole pixels (the
  // sharpest slope rounded), no interpolation. Beside it, the quadrature method at its own
  // sharpest slope, whose blending of neighbouring samples also averages their noise.
  const double wholeSlope = std::round(best.slope);
  auto lightFieldPhotos = [&](std::uint64_t seed) -> Result<std::vector<Image>> {
    LFCAM_ASSIGN_OR_RETURN(auto lf, captureLightField(traced, true, seed));
    SyntheticCamera camera;
    camera.slope = wholeSlope;
    LFCAM_ASSIGN_OR_RETURN(auto views, renderSyntheticPhoto(lf, camera, RenderOptions{RenderMethod::Quadrature, 1}));
    camera.slope = best.quadratureSlope;
    LFCAM_ASSIGN_OR_RETURN(auto quadrature,
                           renderSyntheticPhoto(lf, camera, RenderOptions{RenderMethod::Quadrature, 0}));
    std::vector<Image> both;
    both.push_back(std::move(views));
    both.push_back(std::move(quadrature));
    return both;
  };
  LFCAM_ASSIGN_OR_RETURN(auto lfBoth, measure(lightFieldPhotos, standardFrames, testFrames, mask));
  const Measured& lfMeasured = lfBoth[0];
  const Measured& lfQuadrature = lfBoth[1];
  if (options.progress) options.progress(0.7);

  std::vector<Measured> conventional;
  std::vector<double> lightRatio;
  for (double stop : stops) {
    LFCAM_ASSIGN_OR_RETURN(auto conventionalTraced,
                           traceCapture(chart, conventionalCamera(plenoptic, stop), samples * 4));
    auto photo = [&](std::uint64_t seed) -> Result<std::vector<Image>> {
      LFCAM_ASSIGN_OR_RETURN(auto image, conventionalPhoto(conventionalTraced, true, seed));
      std::vector<Image> one;
      one.push_back(std::move(image));
      return one;
    };
    LFCAM_ASSIGN_OR_RETURN(auto m, measure(photo, standardFrames, testFrames, mask));
    conventional.push_back(std::move(m.front()));
    lightRatio.push_back(totalElectrons(traced) / totalElectrons(conventionalTraced));
  }
  if (options.progress) options.progress(1.0);
  const std::size_t f22 = stops.size() - 1;
  const double ratio = lfMeasured.snr.snr / conventional[f22].snr.snr;
  const double ratioQuadrature = lfQuadrature.snr.snr / conventional[f22].snr.snr;
  const double predicted = std::sqrt(lightRatio[f22]);  // photon shot noise: SNR grows as sqrt(light)

  Report report("Signal-to-noise ratio (Figure 12)");
  report.heading("Setup");
  report.paragraph(
      "The resolution chart at " + fixed(target, 1) + " mm (the camera focused at " +
      fixed(plenoptic.mainLens.focusDistanceMm, 1) + " mm; blur " + fixed(blur, 0) +
      " microlenses at f/4), the same exposure time for every photograph. Light field: " + std::to_string(microlenses) +
      " x " + std::to_string(microlenses) + " microlenses, " + std::to_string(n) +
      " pixels under each, f/4, refocused by adding the views shifted by whole pixels, at slope " +
      fixed(wholeSlope, 0) + " (the sharpest slope for the pinhole target at that distance, " + fixed(best.slope, 3) +
      ", rounded): no interpolation, as the paper added its pixels. " +
      "Also measured: the quadrature method (section 5.2) at its sharpest slope, " + fixed(best.quadratureSlope, 3) +
      ". Conventional: the main lens stopped down, one pixel per microlens gathering the light of " +
      "the pixels it replaces. Sensor: photon shot noise, " + fixed(plenoptic.sensor.readNoiseElectrons, 0) +
      " e- read noise, 12-bit quantisation. Noise-free standard: " + "the mean of " + std::to_string(standardFrames) +
      " frames; noise: rms difference of " + std::to_string(testFrames) +
      " other frames from it (the standard's own residual noise taken out), " + "over the image less a border of " +
      std::to_string(border) + " pixels.");
  report.heading("Results");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < stops.size(); ++i)
    rows.push_back({"conventional f/" + fixed(stops[i], stops[i] < 10 ? 1 : 0), fixed(conventional[i].snr.signal, 4),
                    fixed(conventional[i].snr.noise, 5), fixed(conventional[i].snr.snr, 2),
                    fixed(1 / lightRatio[i], 4)});
  rows.push_back({"light field f/4, refocused (views shifted by whole pixels)", fixed(lfMeasured.snr.signal, 4),
                  fixed(lfMeasured.snr.noise, 5), fixed(lfMeasured.snr.snr, 2), "1"});
  rows.push_back({"light field f/4, refocused (quadrature)", fixed(lfQuadrature.snr.signal, 4),
                  fixed(lfQuadrature.snr.noise, 5), fixed(lfQuadrature.snr.snr, 2), "1"});
  report.table("snr.csv", {"photograph", "signal", "noise (rms)", "SNR", "light relative to the light field"}, rows);
  report.table(
      "summary.csv", {"quantity", "lfcam", "paper"},
      {{"SNR ratio, light field f/4 over conventional f/22", fixed(ratio, 2) + "x", "5.8x"},
       {"the same, refocused by quadrature (interpolation averages noise)", fixed(ratioQuadrature, 2) + "x", "-"},
       {"shot-noise prediction sqrt(light ratio)", fixed(predicted, 2) + "x", "5-6x (25-36 times the light)"},
       {"light ratio", fixed(lightRatio[f22], 1), "25-36"}});
  Plot plot{"SNR against aperture at equal exposure", "image-side f-number", "SNR", true, {}, {}, {}};
  std::vector<double> snrs;
  for (const auto& m : conventional) snrs.push_back(m.snr.snr);
  plot.series.push_back({"conventional", stops, snrs, true, true, false});
  plot.horizontalLines.push_back({"light field f/4, whole-pixel shifts", lfMeasured.snr.snr});
  plot.horizontalLines.push_back({"light field f/4, quadrature", lfQuadrature.snr.snr});
  report.plot("snr.svg", plot,
              "SNR of the conventional photographs against f-number; dashed: the refocused light field.");
  // Each photograph scaled by its standard's brightest pixel (f/22 brightened, as in the paper).
  const int scale = std::max(1, 256 / microlenses);
  auto peak = [](const Image& image) {
    float p = 0;
    for (float v : image.pixels()) p = std::max(p, v);
    return p > 0 ? double(p) : 1.0;
  };
  report.image("conventional_f22.png", forDisplay(conventional[f22].frame, scale, peak(conventional[f22].standard)),
               "Conventional f/22 (one frame)");
  report.image("conventional_f4.png", forDisplay(conventional[0].frame, scale, peak(conventional[0].standard)),
               "Conventional f/4 (one frame)");
  report.image("lightfield_f4.png", forDisplay(lfMeasured.frame, scale, peak(lfMeasured.standard)),
               "Light field f/4, refocused (one frame)");
  report.heading("Against the paper");
  report.paragraph(
      "The paper measured 5.8 times the SNR of the f/22 photograph with the refocused f/4 light field, which " +
      std::string("gathers 25-36 times the light: SNR grows as the square root of the light, so its sensor was ") +
      "limited by photon noise. Here: " + fixed(ratio, 2) + "x measured, " + fixed(predicted, 2) +
      "x predicted by shot noise alone from the light gathered (" + fixed(lightRatio[f22], 1) +
      " times). Refocused by the quadrature method instead, the ratio is " + fixed(ratioQuadrature, 2) +
      "x: its interpolation averages neighbouring samples' noise, and lifts the ratio above the photon-noise law.");
  auto& r = report.results();
  r["experiment"] = "snr";
  r["quick"] = options.quick;
  r["snr_ratio"] = ratio;
  r["snr_ratio_quadrature"] = ratioQuadrature;
  r["light_field_snr_quadrature"] = lfQuadrature.snr.snr;
  r["refocus_slope_quadrature"] = best.quadratureSlope;
  r["predicted_snr_ratio"] = predicted;
  r["paper_snr_ratio"] = 5.8;
  r["light_ratio"] = lightRatio[f22];
  r["light_field_snr"] = lfMeasured.snr.snr;
  r["refocus_slope"] = wholeSlope;
  r["conventional_f_numbers"] = stops;
  r["conventional_snr"] = snrs;
  return report.write(folder);
}

}  // namespace lfcam::experiments
