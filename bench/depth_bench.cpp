// Depth and all-in-focus speed on the HCI "antinous" light field (9x9 views, 512x512 RGB), with
// the table of depth scores printed first: every development scene (depth_scenes.hpp), on which
// the defaults are chosen, and antinous, held out (never used to choose a parameter); its last
// columns: "farther", the share (%) of each scene's BadPix(0.07) pixels put farther than the truth;
// "steep", the share (%) of its pixels on steep slants (steepSlantsOnly), and "steep BP" their
// BadPix(0.07).
//   BM_Refocus      one full-colour refocus: the floor, the unit of work of both operations.
//   BM_Depth        estimateDepth with default options. Counter ratio = time / refocus time.
//   BM_DepthWithoutFill  the same without the edge-aware fill (fillLambda = 0); counter
//                   fill_cost = default time / this time - 1, CPU time of both in this run
//                   (the time shown is of both runs).
//   BM_DepthSubsetsApart  estimateDepth with and without the cost volume's subsets aggregated apart
//                   (src/edof/depth_experiment.hpp), alternating;
//                   counter apart_cost = CPU time with / without - 1 (this run).
//   BM_DepthOcclusionEdges  the same for the occlusion-edge step (occlusionBand 0):
//                   occlusion_cost. These three also show cpu_default_s, CPU seconds per
//                   default run.
//   BM_AllInFocus   allInFocus given the depth map (focal stack + blending). Same counter.
//   BM_DepthAndAllInFocus  both, as `lfcam depth` then `lfcam edof --depth` do: the goal is < 5 s on 2 cores.
//
// Run: build-*/bench/depth_bench [--options FILE.json] [--development-only] [--size N] [--write DIR]
//      [--subsets-together] [--no-noise-correction] [--no-defocus-ceiling] [--flat-cleanup] [--high-pass R]
//      [--gradient A] [--reclaim-first-round-only] [--no-reclaim-cost-check] [--no-first-round-cost-check]
//      [--no-offset-slope-correction] [--offset-shrink] [--no-offset-residual-check]
//      [--no-one-dimensional-gate] [--match-at-reference] [--no-coarse-cost] [--star-ring-step K]
//      [--half-resolution-rounds N] [--scene TEXT] [--stages]
//      [--timings] [--scale] [--benchmark_filter=...]
//   --options           the table with these settings (lfcam depth's options file) instead of the defaults,
//                       each scene keeping its own range: how candidate defaults are compared. Given
//                       more than once, each scene is scored with each file in turn (its row named
//                       with the file's stem), the scenes simulated once
//   --development-only  the table without antinous, for choosing settings (it is held out)
//   --size N            the development scenes at N x N pixels per view (default 128)
//   --scene TEXT        only the development scenes whose name contains TEXT
//   --write DIR         also each scene's map, truth and centre view: DIR/<scene>.pfm, -truth.pfm, -centre.png
//   --stages            under each row, the scores of the map each stage left (the full resolution's
//                       last pass, DepthExperiment::observeStage); with --write, DIR/<scene>-<stage>.pfm
//   --timings           instead of the table: each stage's time on antinous, pass by pass (median of 5),
//                       and the memory floor's bandwidth (design.md, "Depth": the profile); with the first
//                       --options file's settings and the experiment's switches
//   --scale             instead of the table: the time and scores of layered planes of 15 x 15 views of
//                       625 x 434 pixels (a Lytro Illum's) and of their central 5 x 5 views
//   --subsets-together  the cost volume's subsets aggregated together (DepthExperiment): what
//                       aggregating them apart brings
//   --no-noise-correction  without the noise variance that interpolation removes added back
//   --no-defocus-ceiling   the defocus cue not capped at twice the centre view's (DepthExperiment)
//   --flat-cleanup      the weighted median and the occlusion edges without the map's slope
//   --reclaim-first-round-only  the occlusion edges in the first round of refinement and cleanup only
//   --no-reclaim-cost-check  the occlusion edges without the cost volume's veto
//   --no-first-round-cost-check  the veto in the later rounds only, not on the first's narrow parts
//   --no-offset-slope-correction  view offsets measured without taking the map's error out first
//   --offset-shrink     view offsets kept only where larger than a map error could make (DepthExperiment)
//   --no-offset-residual-check  view offsets removed even where they left the views agreeing worse
//   --no-one-dimensional-gate  the centre row and column always among the subsets the lowest is taken of
//   --match-at-reference  views matched at the centre view, not the aperture centre (DepthExperiment)
//   --no-coarse-cost    noisy views matched without the half-resolution cost (DepthExperiment)
//   --star-ring-step K  only every K-th ring of views around the centre in the star (DepthExperiment)
//   --half-resolution-rounds N  refinement and cleanup rounds of the view offsets' half-resolution passes
//   --high-pass R       the experiment of matching views less their local mean (DepthExperiment)
//   --gradient A        the experiment of matching gradients too, with weight A (DepthExperiment)
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/memory_floor.hpp"
#include "depth_scenes.hpp"
#include "edof/depth_experiment.hpp"
#include "lfcam/edof/all_in_focus.hpp"
#include "lfcam/edof/depth.hpp"
#include "lfcam/edof/depth_knobs.hpp"
#include "lfcam/edof/disparity_scores.hpp"
#include "lfcam/io/image_io.hpp"
#include "lfcam/io/light_field_io.hpp"
#include "lfcam/render/refocus.hpp"
#include "lfcam/synth/layered_planes.hpp"

namespace {

using lfcam::LightField, lfcam::LightFieldShape;

// The real data: LFCAM_DATA_DIR, as the tests take it, else the folder beside the repository.
const std::string kFolder =
    std::string(std::getenv("LFCAM_DATA_DIR") ? std::getenv("LFCAM_DATA_DIR") : LFCAM_SHARED_DATA_DIR) +
    "/hci-antinous";

const LightField& antinous() {
  static const LightField lightField = [] {
    auto read = lfcam::readLightField(kFolder);
    if (read) return std::move(read).value();
    std::fprintf(stderr,
                 "depth_bench: cannot read %s (%s);\n  using a layered-planes light field of 9x9 views, 512x512\n",
                 kFolder.c_str(), read.error().message.c_str());
    return std::move(lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(9, 512)).lightField);
  }();
  return lightField;
}

double refocusSeconds = 0;

void BM_Refocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(lfcam::refocus(lightField, 0.5));
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  refocusSeconds = total / double(state.iterations());
}

void reportRatio(benchmark::State& state, double seconds) {
  if (refocusSeconds > 0) state.counters["ratio_to_refocus"] = seconds / refocusSeconds;
}

void BM_Depth(benchmark::State& state) {
  const LightField& lightField = antinous();
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto depth = lfcam::estimateDepth(lightField);
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!depth) state.SkipWithError(depth.error().message.c_str());
  }
  reportRatio(state, total / double(state.iterations()));
}

// CPU time of the process (every thread): on a shared machine closer to the work done than wall time.
double processCpuSeconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

// Process CPU time of estimateDepth with `without` and with the default options, alternating
// (the state's iterations each run both); returns with / without - 1.
double extraCpuOfDefault(benchmark::State& state, const lfcam::DepthOptions& without,
                         const lfcam::edof::DepthExperiment& experiment = {}) {
  const LightField& lightField = antinous();
  auto timeDepth = [&](const lfcam::DepthOptions& options, const lfcam::edof::DepthExperiment& switches) {
    const double start = processCpuSeconds();
    auto depth = lfcam::edof::estimateDepth(lightField, options, switches);
    if (!depth) state.SkipWithError(depth.error().message.c_str());
    return processCpuSeconds() - start;
  };
  double withSeconds = 0, withoutSeconds = 0;
  for (auto _ : state) {
    withSeconds += timeDepth({}, {});
    withoutSeconds += timeDepth(without, experiment);
  }
  state.counters["cpu_default_s"] = withSeconds / double(state.iterations());
  return withoutSeconds > 0 ? withSeconds / withoutSeconds - 1 : 0.0;
}

void BM_DepthWithoutFill(benchmark::State& state) {
  state.counters["fill_cost"] = extraCpuOfDefault(state, {.fillLambda = 0.0});
}

void BM_DepthSubsetsApart(benchmark::State& state) {
  state.counters["apart_cost"] = extraCpuOfDefault(state, {}, {.aggregateSubsetsApart = false});
}

// The occlusion-edge step (src/edof/occlusion_edges.cpp): CPU with it over without, same run.
void BM_DepthOcclusionEdges(benchmark::State& state) {
  state.counters["occlusion_cost"] = extraCpuOfDefault(state, {.occlusionBand = 0});
}

void BM_AllInFocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  auto depth = lfcam::estimateDepth(lightField);
  if (!depth) return state.SkipWithError(depth.error().message.c_str());
  double total = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    auto photo = lfcam::allInFocus(lightField, {.disparity = &depth->disparity});
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!photo) state.SkipWithError(photo.error().message.c_str());
  }
  reportRatio(state, total / double(state.iterations()));
}

void BM_DepthAndAllInFocus(benchmark::State& state) {
  const LightField& lightField = antinous();
  for (auto _ : state) {
    auto depth = lfcam::estimateDepth(lightField);
    if (!depth) return state.SkipWithError(depth.error().message.c_str());
    auto photo = lfcam::allInFocus(lightField, {.disparity = &depth->disparity});
    if (!photo) return state.SkipWithError(photo.error().message.c_str());
  }
}

BENCHMARK(BM_Refocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_Depth)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthWithoutFill)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthSubsetsApart)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_DepthOcclusionEdges)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_AllInFocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_DepthAndAllInFocus)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// The truth on steep slants only, NaN elsewhere (scoreDisparity skips those pixels): where the
// disparity changes by kSteep to kJump px per pixel towards a 4-neighbour (by the larger of the
// central differences across and down), and no neighbour lies across a jump.
lfcam::Image steepSlantsOnly(const lfcam::Image& truth) {
  constexpr float kSteep = 0.02f, kJump = 0.3f;
  lfcam::Image steep(truth.width(), truth.height(), 1);
  for (float& value : steep.pixels()) value = NAN;
  for (int y = 1; y + 1 < truth.height(); ++y)
    for (int x = 1; x + 1 < truth.width(); ++x) {
      const float centre = truth.at(x, y, 0);
      const float neighbours[4] = {truth.at(x - 1, y, 0), truth.at(x + 1, y, 0), truth.at(x, y - 1, 0),
                                   truth.at(x, y + 1, 0)};
      bool smooth = std::isfinite(centre);
      for (float n : neighbours) smooth = smooth && std::isfinite(n) && std::abs(n - centre) < kJump;
      const float slope =
          std::max(std::abs(neighbours[1] - neighbours[0]), std::abs(neighbours[3] - neighbours[2])) / 2;
      if (smooth && slope >= kSteep) steep.at(x, y, 0) = centre;
    }
  return steep;
}

// A set of settings the table is printed with, and its name in the rows.
struct Candidate {
  std::string label;
  lfcam::DepthOptions options;
};

// One row of the scores table.
void printRow(const std::string& name, const lfcam::DepthMap& depth, const lfcam::Image& truth, double seconds) {
  auto scores = lfcam::scoreHci(depth.disparity, truth);
  auto strict = lfcam::scoreDisparity(depth.disparity, truth, 0.07);
  auto steep = lfcam::scoreDisparity(depth.disparity, steepSlantsOnly(truth), 0.07);
  if (!scores) return (void)std::printf("%-28s %s\n", name.c_str(), scores.error().message.c_str());
  std::printf("%-28s %8.2f %8.2f %9.3f %9.3f %7.2f %9.2g %9.2f %8.0f", name.c_str(), scores->badPix007,
              scores->badPix003, scores->mse100, scores->bumpiness, seconds, depth.viewResidual, depth.prefilterSigma,
              strict ? strict->fartherShare : 0.0);
  if (steep && strict)
    std::printf(" %6.1f %8.2f\n", 100.0 * double(steep->pixels) / double(strict->pixels), steep->badPix);
  else
    std::printf(" %6s %8s\n", "0", "-");
}

// A scene's map as each stage left it, in the order the stages first ran, at the truth's size: a
// later pass's map (noisy views are matched twice) replaces the earlier one's.
struct StageMaps {
  int width = 0, height = 0;
  std::vector<std::pair<std::string, lfcam::Image>> maps;

  void observe(const std::string& stage, const lfcam::Image& disparity) {
    if (disparity.width() != width || disparity.height() != height) return;
    for (auto& [name, map] : maps)
      if (name == stage) return void(map = disparity.copy());
    maps.emplace_back(stage, disparity.copy());
  }
};

// Each stage's scores, indented under the scene's row.
void printStages(const StageMaps& stages, const lfcam::Image& truth) {
  for (const auto& [stage, map] : stages.maps)
    if (auto scores = lfcam::scoreHci(map, truth))
      std::printf("  %-26s %8.2f %8.2f %9.3f %9.3f\n", stage.c_str(), scores->badPix007, scores->badPix003,
                  scores->mse100, scores->bumpiness);
}

// Every scene's HCI scores with each of `candidates` (disparity_scores.hpp; 15-pixel border;
// bumpiness on the planes of the ground truth): the development scenes, on which defaults are
// chosen, then HCI antinous, held out: never used to choose a parameter. With more than one
// candidate, each row is named with its label. With `folder` not empty, each scene's disparity,
// truth and centre view are written there. With `stages`, each stage's scores (and maps) too.
void printScores(const std::vector<Candidate>& candidates, const lfcam::edof::DepthExperiment& experiment, bool heldOut,
                 const std::string& folder, int size, const std::string& only, bool stages) {
  const auto writeMap = [&](const std::string& stem, const std::string& suffix, const lfcam::Image& image) {
    if (auto written = lfcam::writeImage(folder + "/" + stem + suffix, image); !written)
      std::fprintf(stderr, "depth_bench: %s\n", written.error().message.c_str());
  };
  // One row: the map of `lightField` with `options`, scored against `truth` (and its stages').
  const auto run = [&](const std::string& row, const LightField& lightField, const lfcam::DepthOptions& options,
                       const lfcam::Image& truth) {
    StageMaps stageMaps{truth.width(), truth.height(), {}};
    lfcam::edof::DepthExperiment observed = experiment;
    if (stages)
      observed.observeStage = [&](const std::string& stage, const lfcam::Image& map) { stageMaps.observe(stage, map); };
    const auto start = std::chrono::steady_clock::now();
    auto depth = lfcam::edof::estimateDepth(lightField, options, observed);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!depth) return (void)std::printf("%-28s %s\n", row.c_str(), depth.error().message.c_str());
    printRow(row, *depth, truth, seconds);
    printStages(stageMaps, truth);
    if (folder.empty()) return;
    std::string stem = row;  // without a parenthesis, "(held out)"
    if (const auto open = stem.find(" ("); open != std::string::npos) stem.erase(open, stem.find(')', open) - open + 1);
    for (char& c : stem)
      if (c == ' ' || c == ',') c = '-';
    writeMap(stem, ".pfm", depth->disparity);
    writeMap(stem, "-truth.pfm", truth);
    writeMap(stem, "-centre.png", lightField.subApertureImage((lightField.nu() - 1) / 2, (lightField.nv() - 1) / 2));
    for (const auto& [stage, map] : stageMaps.maps) {
      std::string suffix = "-" + stage + ".pfm";
      for (char& c : suffix)
        if (c == ' ') c = '-';
      writeMap(stem, suffix, map);
    }
  };
  std::printf("%-28s %8s %8s %9s %9s %7s %9s %9s %8s %6s %8s\n", "scene", "BP(0.07)", "BP(0.03)", "MSEx100",
              "bumpiness", "seconds", "residual", "prefilter", "farther", "steep", "steep BP");
  const auto rowName = [&](const std::string& scene, const Candidate& candidate) {
    return candidates.size() > 1 ? scene + " [" + candidate.label + "]" : scene;
  };
  for (const lfcam::bench::DepthScene& scene : lfcam::bench::developmentScenes(size)) {
    if (scene.name.find(only) == std::string::npos) continue;
    for (const Candidate& candidate : candidates) {
      lfcam::DepthOptions sceneOptions = candidate.options;
      sceneOptions.disparityMin = scene.disparityMin;
      sceneOptions.disparityMax = scene.disparityMax;
      run(rowName(scene.name, candidate), scene.lightField, sceneOptions, scene.disparity);
    }
  }
  if (!heldOut) return;
  auto truth = lfcam::readImage(kFolder + "/gt_disp_lowres.pfm");
  if (!truth) return (void)std::printf("hci-antinous (held out): not found in %s\n", kFolder.c_str());
  for (const Candidate& candidate : candidates)
    run(rowName("hci-antinous (held out)", candidate), antinous(), candidate.options, *truth);
}

// Where estimateDepth's time goes on antinous (DepthExperiment::stageEnded): each stage's wall
// seconds per pass (the half-resolution passes, then full resolution), the median of `runs`, and its
// share; then the memory floor's bandwidth, measured between the runs (memory_floor.hpp).
void printTimings(int runs, const lfcam::DepthOptions& options, const lfcam::edof::DepthExperiment& experiment) {
  const LightField& lightField = antinous();
  struct Stage {
    std::string pass, name;
    std::vector<double> seconds;
  };
  std::vector<Stage> stages;
  lfcam::MemoryFloor floor(1.0);
  for (int run = 0; run < runs; ++run) {
    floor.measure();
    std::size_t index = 0;
    int pass = 0;
    auto last = std::chrono::steady_clock::now();
    lfcam::edof::DepthExperiment timed = experiment;
    timed.stageEnded = [&](const std::string& name) {
      const auto now = std::chrono::steady_clock::now();
      if (name == "views") ++pass;
      if (index == stages.size()) stages.push_back({"pass " + std::to_string(pass), name, {}});
      stages[index++].seconds.push_back(std::chrono::duration<double>(now - last).count());
      last = now;
    };
    if (auto depth = lfcam::edof::estimateDepth(lightField, options, timed); !depth)
      return (void)std::fprintf(stderr, "depth_bench: %s\n", depth.error().message.c_str());
  }
  double total = 0;
  for (const Stage& stage : stages) total += lfcam::medianOf(stage.seconds);
  std::printf("%-8s %-12s %9s %7s   (median of %d runs; passes 1-%d: half resolution, last: full)\n", "pass", "stage",
              "seconds", "share", runs, int(stages.empty() ? 0 : std::stoi(stages.back().pass.substr(5))) - 1);
  for (const Stage& stage : stages) {
    const double seconds = lfcam::medianOf(stage.seconds);
    std::printf("%-8s %-12s %9.3f %6.1f%%\n", stage.pass.c_str(), stage.name.c_str(), seconds, 100 * seconds / total);
  }
  std::printf("%-21s %9.3f\nmemory floor: %.1f GB/s (read + write, threaded copy, median)\n", "total", total,
              floor.medianBandwidth() / 1e9);
}

// How the time grows (issue 51): the layered planes at the size of a Lytro Illum's views (625 x 434)
// with 15 x 15 views and with its central 5 x 5, each timed once and scored.
void printScale() {
  const lfcam::LayeredPlanesLightField illum =
      lfcam::renderLayeredPlanes(lfcam::defaultLayeredPlanesScene(15, 625, 1, 434));
  LightFieldShape shape = illum.lightField.shape();
  shape.nu = shape.nv = 5;
  LightField centre(shape);
  centre.metadata = illum.lightField.metadata;
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 5; ++u) centre.setSubApertureImage(u, v, illum.lightField.subApertureImage(u + 5, v + 5));
  std::printf("%-8s %9s %7s %8s %9s %9s\n", "views", "pixels", "labels", "seconds", "ns/label", "BP(0.07)");
  for (const LightField* lightField : {&illum.lightField, static_cast<const LightField*>(&centre)}) {
    const auto start = std::chrono::steady_clock::now();
    auto depth = lfcam::estimateDepth(*lightField);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!depth) return (void)std::fprintf(stderr, "depth_bench: %s\n", depth.error().message.c_str());
    const auto scores = lfcam::scoreHci(depth->disparity, illum.disparity);
    const double pixels = double(lightField->ns()) * lightField->nt();
    std::printf("%2dx%-5d %9.0f %7d %8.2f %9.1f %9.2f\n", lightField->nu(), lightField->nv(), pixels, depth->labels,
                seconds, 1e9 * seconds / (pixels * depth->labels), scores ? scores->badPix007 : NAN);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // The table's own flags, taken out before the benchmark library reads the rest.
  std::vector<Candidate> candidates;
  lfcam::edof::DepthExperiment experiment;
  bool heldOut = true, stages = false, timings = false, scale = false;
  std::string folder, only;
  int kept = 1, size = 128;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--development-only") {
      heldOut = false;
    } else if (argument == "--size" && i + 1 < argc) {
      size = std::atoi(argv[++i]);
    } else if (argument == "--scene" && i + 1 < argc) {
      only = argv[++i];
    } else if (argument == "--stages") {
      stages = true;
    } else if (argument == "--timings") {
      timings = true;
    } else if (argument == "--scale") {
      scale = true;
    } else if (argument == "--write" && i + 1 < argc) {
      folder = argv[++i];
    } else if (argument == "--gradient" && i + 1 < argc) {
      experiment.gradientWeight = std::atof(argv[++i]);
    } else if (argument == "--subsets-together") {
      experiment.aggregateSubsetsApart = false;
    } else if (argument == "--no-noise-correction") {
      experiment.noiseCorrection = false;
    } else if (argument == "--no-one-dimensional-gate") {
      experiment.oneDimensionalGate = false;
    } else if (argument == "--no-defocus-ceiling") {
      experiment.defocusCeiling = false;
    } else if (argument == "--flat-cleanup") {
      experiment.slantedCleanup = false;
    } else if (argument == "--no-reclaim-cost-check") {
      experiment.reclaimCostCheck = false;
    } else if (argument == "--no-first-round-cost-check") {
      experiment.firstRoundCostCheck = false;
    } else if (argument == "--no-coarse-cost") {
      experiment.noisyCoarseCost = false;
    } else if (argument == "--match-at-reference") {
      experiment.matchAtReference = true;
    } else if (argument == "--no-offset-slope-correction") {
      experiment.offsetSlopeCorrection = false;
    } else if (argument == "--offset-shrink") {
      experiment.offsetShrink = true;
    } else if (argument == "--no-offset-residual-check") {
      experiment.offsetResidualCheck = false;
    } else if (argument == "--reclaim-first-round-only") {
      experiment.reclaimEveryRound = false;
    } else if (argument == "--star-ring-step" && i + 1 < argc) {
      experiment.starRingStep = std::atoi(argv[++i]);
    } else if (argument == "--half-resolution-rounds" && i + 1 < argc) {
      experiment.halfResolutionRounds = std::atoi(argv[++i]);
    } else if (argument == "--high-pass" && i + 1 < argc) {
      experiment.highPassRadius = std::atoi(argv[++i]);
    } else if (argument == "--options" && i + 1 < argc) {
      const std::filesystem::path file = argv[++i];
      Candidate candidate{file.stem().string(), {}};
      if (auto read = lfcam::readDepthOptions(file, candidate.options); !read)
        return std::fprintf(stderr, "depth_bench: %s\n", read.error().message.c_str()), 2;
      candidates.push_back(std::move(candidate));
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (candidates.empty()) candidates.push_back({"defaults", {}});
  if (timings) return printTimings(5, candidates.front().options, experiment), 0;
  if (scale) return printScale(), 0;
  printScores(candidates, experiment, heldOut, folder, size, only, stages);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
