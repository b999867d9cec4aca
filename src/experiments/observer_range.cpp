// Figure 6: where a synthetic pinhole camera can stand (Equation 7: across the lens plane by u,
// along the axis by beta) and still see the whole field without vignetting, at two focus
// settings (magnifications). Found by rendering: the observer's photograph of a white field is
// vignetted when some pixel receives no ray.
#include <cmath>

#include "experiments/experiment_support.hpp"
#include "lfcam/render/synthetic_camera.hpp"

namespace lfcam::experiments {

namespace {

// No pixel without light.
Result<bool> unvignetted(const LightField& lf, double u, double beta) {
  const Optics& optics = *lf.metadata.optics;
  Observer observer{
      .u = u, .v = 0, .beta = beta, .parallax = optics.lensStepMm / optics.spatialStepMm, .clampToLens = false};
  LFCAM_ASSIGN_OR_RETURN(auto photo, observe(lf, observer));
  for (float value : photo.pixels())
    if (!(value > 0.5f)) return false;
  return true;
}

struct Region {
  double focusMm = 0, magnification = 0, imageDistanceMm = 0, lensStepMm = 0;
  std::vector<double> beta, halfWidth;  // halfWidth < 0: no position at this beta
};

}  // namespace

Status runObserverRange(const std::filesystem::path& folder, const ExperimentOptions& options) {
  const int microlenses = options.quick ? 16 : 48, n = 12, betaSteps = options.quick ? 17 : 49;
  const std::vector<double> focusDistances{457.2, 1828.8};  // 18 and 72 inches
  std::vector<Region> regions;
  for (double focus : focusDistances) {
    const CameraModel camera = plenopticCamera(microlenses, n, focus);
    LFCAM_ASSIGN_OR_RETURN(auto traced, traceCapture(whiteScene(), camera, 4));
    LFCAM_ASSIGN_OR_RETURN(auto lf, captureLightField(traced, false, 1));
    Region region;
    region.focusMm = focus;
    region.imageDistanceMm = camera.mainLens.imageDistanceMm();
    region.magnification = region.imageDistanceMm / focus;
    region.lensStepMm = lf.metadata.optics->lensStepMm;
    for (int k = 0; k < betaSteps; ++k) {
      // beta from 1/2 to 2, evenly in log: the synthetic lens plane from F/2 to 2F before the microlenses.
      const double beta = std::pow(2.0, -1.0 + 2.0 * k / (betaSteps - 1));
      double half = -1;
      LFCAM_ASSIGN_OR_RETURN(auto centre, unvignetted(lf, 0, beta));
      if (centre) {
        // Bisection for the farthest |u| (the region is symmetric about the axis).
        double lo = 0, hi = 0.5 * n + 1;
        for (int it = 0; it < 12; ++it) {
          const double mid = 0.5 * (lo + hi);
          LFCAM_ASSIGN_OR_RETURN(auto ok, unvignetted(lf, mid, beta));
          (ok ? lo : hi) = mid;
        }
        half = lo;
      }
      region.beta.push_back(beta);
      region.halfWidth.push_back(half);
    }
    regions.push_back(std::move(region));
    if (options.progress) options.progress(double(regions.size()) / focusDistances.size());
  }

  Report report("Observer range (Figure 6)");
  report.heading("Setup");
  report.paragraph(
      "A white field captured with " + std::to_string(microlenses) + " x " + std::to_string(microlenses) +
      " microlenses and " + std::to_string(n) + " pixels under each, the main lens at image-side f/4 focused at " +
      "18 and at 72 inches. A synthetic pinhole (Equation 7) at lens position x = u du and at the plane beta F in " +
      "front of the microlens plane (z = (1 - beta) F behind the main lens, negative: in front of it); its " +
      "photograph is vignetted when some pixel receives no ray. For each beta the farthest |x| is found by bisection.");
  report.heading("Results");
  Plot plot{"Pinhole positions without vignetting",
            "z, distance behind the main lens relative to F",
            "x / scene distance",
            false,
            {},
            {},
            {}};
  std::vector<std::vector<std::string>> rows;
  auto& r = report.results();
  r["experiment"] = "observer-range";
  r["quick"] = options.quick;
  r["regions"] = nlohmann::json::array();
  for (const Region& region : regions) {
    Series shaded{"focus " + fixed(region.focusMm / 25.4, 0) + " in (m = " + fixed(region.magnification, 3) + ")",
                  {},
                  {},
                  true,
                  false,
                  true};
    double lateral = 0, betaMin = INFINITY, betaMax = 0, area = 0;
    std::vector<std::pair<double, double>> upper;
    for (std::size_t k = 0; k < region.beta.size(); ++k) {
      const double z = 1 - region.beta[k];  // F units
      const double xMm = region.halfWidth[k] * region.lensStepMm;
      rows.push_back({fixed(region.focusMm, 1), fixed(region.beta[k], 3), fixed(z * region.imageDistanceMm, 2),
                      region.halfWidth[k] < 0 ? "none" : fixed(2 * xMm, 3)});
      if (region.halfWidth[k] < 0) continue;
      upper.emplace_back(z, xMm / region.focusMm);
      betaMin = std::min(betaMin, region.beta[k]);
      betaMax = std::max(betaMax, region.beta[k]);
      if (std::abs(region.beta[k] - 1) < 1e-9) lateral = 2 * xMm;
      if (k > 0 && region.halfWidth[k - 1] >= 0)
        area += std::abs(region.beta[k] - region.beta[k - 1]) * region.imageDistanceMm *
                (region.halfWidth[k] + region.halfWidth[k - 1]) * region.lensStepMm;
    }
    for (const auto& [z, x] : upper) shaded.x.push_back(z), shaded.y.push_back(x);
    for (auto it = upper.rbegin(); it != upper.rend(); ++it)
      shaded.x.push_back(it->first), shaded.y.push_back(-it->second);
    plot.series.push_back(std::move(shaded));
    r["regions"].push_back({{"focus_distance_mm", region.focusMm},
                            {"magnification", region.magnification},
                            {"lateral_range_mm", lateral},
                            {"lateral_range_over_distance", lateral / region.focusMm},
                            {"beta_min", std::isfinite(betaMin) ? betaMin : 0.0},
                            {"beta_max", betaMax},
                            {"area_mm2", area}});
  }
  report.table("range.csv", {"focus (mm)", "beta", "z (mm)", "unvignetted width 2|x| (mm)"}, rows);
  report.plot("range.svg", plot,
              "Shaded: where the pinhole may stand (x relative to the scene distance), for the two focus settings.");
  const auto& a = r["regions"][0];
  const auto& b = r["regions"][1];
  r["lateral_range_over_distance"] = {a["lateral_range_over_distance"], b["lateral_range_over_distance"]};
  r["magnifications"] = {a["magnification"], b["magnification"]};
  r["shrink_factor"] = double(a["lateral_range_over_distance"]) > 0
                           ? double(b["lateral_range_over_distance"]) / double(a["lateral_range_over_distance"])
                           : 0.0;
  report.heading("Against the paper");
  report.paragraph(
      "The paper: the space shrinks relative to the distance to the scene as the magnification decreases, so close-up "
      "photography allows the greatest movement of the observer. Here the unvignetted width at the lens plane is " +
      fixed(double(a["lateral_range_over_distance"]) * 100, 2) + "% of the scene distance at magnification " +
      fixed(double(a["magnification"]), 3) + " and " + fixed(double(b["lateral_range_over_distance"]) * 100, 2) +
      "% at " + fixed(double(b["magnification"]), 3) + ".");
  return report.write(folder);
}

}  // namespace lfcam::experiments
