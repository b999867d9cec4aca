// Section 4.2: "if the image under the microlenses is N pixels across, then we can digitally
// refocus such that any desired region is geometrically sharper by a factor of N". The pinhole
// at a fixed defocus, light fields with N = 4..16 pixels per microlens, each refocused to its
// sharpest; its 75%-energy cutoff against N, with a straight line fitted.
#include <algorithm>
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/analysis/analysis.hpp"

namespace lfcam::experiments {

Status runSharpnessVsN(const std::filesystem::path& folder, const ExperimentOptions& options) {
  const int microlenses = options.quick ? 32 : 40;
  const double blur = options.quick ? 24 : 32;  // wide enough that 16 views still leave blur to remove
  const double hits = options.quick ? 12 : 24;  // ray samples per pixel over (blur / N + 1)^2
  const std::vector<int> counts =
      options.quick ? std::vector<int>{4, 6, 8, 10} : std::vector<int>{4, 6, 8, 10, 12, 14, 16};

  std::vector<double> ns, cutoffs, slopes;
  std::vector<int> samplesUsed;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    const int n = counts[k];
    const CameraModel plenoptic = plenopticCamera(microlenses, n);
    const Scene pinhole = pinholeScene(plenoptic, defocusedDistanceMm(plenoptic, blur));
    // Monte Carlo noise: a pixel's rays land on a patch of the target (blur / N + 1) microlenses
    // across, of which the pinhole (one microlens) is a small part; speckle from too few hits
    // would pass for detail. About 24 (blur / N + 1)^2 rays per pixel, in traces of at most 1024.
    const double footprint = blur / n + 1;
    const int rays = int(std::ceil(hits * footprint * footprint)), traces = (rays + 1023) / 1024;
    const int samples = (rays + traces - 1) / traces;
    samplesUsed.push_back(samples * traces);
    LFCAM_ASSIGN_OR_RETURN(auto traced, traceCapture(pinhole, plenoptic, samples, traces));
    LFCAM_ASSIGN_OR_RETURN(auto lightField, captureLightField(traced, false, 1));
    LFCAM_ASSIGN_OR_RETURN(auto best, refocusToSharpest(lightField));
    ns.push_back(n);
    cutoffs.push_back(best.cutoff);
    slopes.push_back(best.slope);
    if (options.progress) options.progress(double(k + 1) / counts.size());
  }
  LFCAM_ASSIGN_OR_RETURN(auto fit, fitLine(ns, cutoffs));

  Report report("Sharpness against pixels per microlens (section 4.2)");
  report.heading("Setup");
  report.paragraph(
      "The pinhole target at the distance where its blur through the f/4 aperture is " + fixed(blur, 0) +
      " microlenses across; " + std::to_string(microlenses) + " x " + std::to_string(microlenses) +
      " microlenses of 125 um at f/4; the pixel pitch chosen so that N x N pixels lie under each microlens. " +
      "Each raw frame (noise-free; about " + fixed(hits, 0) +
      " (blur/N + 1)^2 ray samples per pixel, so that every pixel's rays hit " +
      "the pinhole often enough that Monte Carlo speckle does not pass for detail) is decoded, refocused by " +
      "shift-and-add of the views at the slope of highest cutoff (searched near the slope where the point is " +
      "most concentrated), and the cutoff (75% of the transfer function's energy, cycles per microlens) recorded. " +
      "Where the slope is not a whole number of pixels, the views' bilinear taps add up to half a pixel of blur.");
  report.heading("Results");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < ns.size(); ++i)
    rows.push_back({fixed(ns[i], 0), fixed(cutoffs[i], 4), fixed(slopes[i], 3),
                    fixed(fit.slope * ns[i] + fit.intercept, 4), std::to_string(samplesUsed[i])});
  report.table(
      "sharpness.csv",
      {"N (pixels per microlens)", "cutoff (cycles/microlens)", "refocus slope", "linear fit", "ray samples per pixel"},
      rows);
  report.table("summary.csv", {"quantity", "lfcam", "paper"},
               {{"slope of the fit (cycles/microlens per pixel of N)", fixed(fit.slope, 5), "-"},
                {"intercept", fixed(fit.intercept, 4), "-"},
                {"R^2", fixed(fit.r2, 4), "linear (claimed, not measured)"}});
  Plot plot{
      "Refocused sharpness against N", "N (pixels per microlens)", "cutoff (cycles per microlens)", false, {}, {}, {}};
  plot.series.push_back({"measured", ns, cutoffs, false, true, false});
  plot.series.push_back({"fit, R^2 = " + fixed(fit.r2, 3),
                         {ns.front(), ns.back()},
                         {fit.slope * ns.front() + fit.intercept, fit.slope * ns.back() + fit.intercept},
                         true,
                         false,
                         false});
  report.plot("sharpness.svg", plot,
              "Cutoff of the refocused pinhole against the number of pixels under each microlens, with the "
              "least-squares line.");
  report.heading("Against the paper");
  report.paragraph(
      "Section 4.2 predicts sharpness growing linearly with N (the sub-aperture images' blur is N times "
      "narrower); the paper does not measure it. Here the fit gives slope " +
      fixed(fit.slope, 5) + " and R^2 = " + fixed(fit.r2, 4) +
      ". The line flattens once the refocused blur nears one microlens, "
      "the spatial sampling of the light field (and the pinhole, itself a microlens across), and it wobbles where "
      "the " +
      "refocus slope is not a whole number of pixels (bilinear taps).");
  auto& r = report.results();
  r["experiment"] = "sharpness-vs-n";
  r["quick"] = options.quick;
  r["slope"] = fit.slope;
  r["intercept"] = fit.intercept;
  r["r2"] = fit.r2;
  r["n"] = ns;
  r["cutoffs"] = cutoffs;
  r["blur_microlenses"] = blur;
  r["ray_samples_per_pixel"] = samplesUsed;
  return report.write(folder);
}

}  // namespace lfcam::experiments
