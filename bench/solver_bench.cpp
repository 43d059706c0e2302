// Benchmark: the solver's stages on contribution-like matrices (a wall of square elements seen
// from sensors in a room: E(i, j) is the element's view factor), goals made from known openings.
// Wall-clock seconds on this machine; noisy.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "annual/annual_contributions.h"
#include "scene/scene.h"
#include "solve/genetic.h"
#include "solve/linear_start.h"
#include "solve/nnls.h"
#include "solve/solver.h"
#include "trace/contributions_origin.h"
#include "util/rng.h"

namespace {

using namespace fenestra;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Problem {
  LinearObjective objective;
  ElementGrid grid;
  std::vector<uint8_t> truth;
};

// Elements of side a on the wall y = 0 (rows up, columns along x); sensors on a work plane
// 0.8 m high, facing up, between 0.5 and 6 m from the wall.
Problem make_problem(int sensors, int rows, int cols) {
  Problem p;
  p.grid = ElementGrid::rectangle(rows, cols);
  const double a = 0.3, width = cols * a;
  Rng rng(7, 1);
  p.objective.E.resize(sensors, rows * cols);
  for (int i = 0; i < sensors; ++i) {
    const double sx = width * rng.uniform(), sy = 0.5 + 5.5 * rng.uniform(), sz = 0.8;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double dx = (c + 0.5) * a - sx, dy = -sy, dz = 1.0 + (r + 0.5) * a - sz;
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double cos_sensor = std::max(0.0, dz) / std::sqrt(d2), cos_wall = sy / std::sqrt(d2);
        p.objective.E(i, r * cols + c) = 1000.0 * a * a * cos_sensor * cos_wall / (3.14159265 * d2);
      }
  }
  // Two windows.
  p.truth.assign(rows * cols, 0);
  for (int r = rows / 4; r < rows / 2; ++r)
    for (int c = cols / 8; c < cols / 3; ++c) p.truth[r * cols + c] = 1;
  for (int r = rows / 5; r < 3 * rows / 4; ++r)
    for (int c = cols / 2; c < 3 * cols / 4; ++c) p.truth[r * cols + c] = 1;
  Eigen::VectorXd o(rows * cols);
  for (int k = 0; k < rows * cols; ++k) o[k] = p.truth[k];
  p.objective.target = p.objective.E * o;
  p.objective.weight = Eigen::VectorXd::Constant(sensors, 1.0 / p.objective.target.squaredNorm());
  return p;
}

void run(int sensors, int rows, int cols) {
  const Problem p = make_problem(sensors, rows, cols);
  const auto t0 = Clock::now();
  const Eigen::VectorXd sqrt_w = p.objective.weight.cwiseSqrt();
  const NnlsResult r = nnls(sqrt_w.asDiagonal() * p.objective.E, sqrt_w.cwiseProduct(p.objective.target));
  Eigen::VectorXd x = r.x;
  redistribute_excess(p.grid, &x);
  const std::vector<uint8_t> start = round_to_binary(x);
  const double nnls_s = since(t0);
  const auto t1 = Clock::now();
  GeneticSettings ga;
  ga.shape.boundary = 1e-5 * 20.0 / std::max(rows, cols);  // finer grids: lighter per-edge weight
  const GeneticResult g = run_genetic(p.objective, p.grid, {start}, ga);
  const double ga_s = since(t1);
  Eigen::VectorXd o(p.grid.size());
  for (int k = 0; k < p.grid.size(); ++k) o[k] = g.best[k];
  const double rms = (p.objective.E * o - p.objective.target).norm() / p.objective.target.norm();
  int wrong = 0;
  for (int k = 0; k < p.grid.size(); ++k) wrong += g.best[k] != p.truth[k];
  std::printf("    %5d sensors x %5d elements: NNLS + rounding %.3f s (%d iterations), genetic %.3f s "
              "(%d generations, population %d) -> total %.3f s; relative RMS %.2f%%, %d elements differ from the "
              "truth\n",
              sensors, rows * cols, nnls_s, r.iterations, ga_s, g.generations, ga.population, nnls_s + ga_s,
              100.0 * rms, wrong);
}

// A re-solve as the add-on makes it after the goals were repainted: the contributions kept, the
// solver's stages at the add-on's Preview settings (its check with real cutters at 512 paths).
// Returns the median run's seconds.
double resolve(const std::string& path) {
  Scene scene = load_scene(path);
  scene.solver.verify_paths = 512;
  if (scene.solver.paths_per_sensor > 0) scene.render.paths_per_sensor = scene.solver.paths_per_sensor;
  Contributions c = compute_contributions(scene);
  c.origin = contributions_origin(scene);
  std::vector<SolveResult> runs;
  for (int i = 0; i < 3; ++i) runs.push_back(solve_openings(scene, c));
  std::sort(runs.begin(), runs.end(), [](const SolveResult& a, const SolveResult& b) {
    return a.timings.back().seconds < b.timings.back().seconds;
  });
  const SolveResult& median = runs[1];
  std::printf("    %s: %zu sensors x %zu elements, %d paths per sensor; median of 3: %.3f s (",
              path.c_str(), scene.sensors.size(), c.element_count(), c.paths_per_sensor, median.timings.back().seconds);
  for (size_t i = 0; i + 1 < median.timings.size(); ++i)
    std::printf("%s%s %.3f", i ? ", " : "", median.timings[i].stage.c_str(), median.timings[i].seconds);
  std::printf("); %zu openings, %d edge moves, error %.2f%% (checked %.2f%%)\n", median.openings.size(),
              median.edge_moves, 100.0 * median.error.relative_rms, 100.0 * median.verified_error.relative_rms);
  return median.timings.back().seconds;
}

// The target for a re-solve of the thick-walled room at Preview (an architect repainting goals).
constexpr double kThickResolveTargetSeconds = 1.5;

}  // namespace

int main(int argc, char** argv) {
  const bool resolve_only = argc == 2 && std::string(argv[1]) == "--resolve";  // the re-solve alone
  if (!resolve_only) {
    std::printf("[solver] NNLS start + genetic algorithm on view-factor matrices, goals from two known windows\n");
    run(100, 10, 20);
    run(1000, 100, 100);
  }
  std::printf("[solver] re-solve with the contributions kept (Preview, as the add-on after repainting goals)\n");
  resolve(FENESTRA_EXAMPLES "/room_study/scene.json");
  const double thick = resolve(FENESTRA_EXAMPLES "/thick_walls_study/scene.json");
  std::printf("    target: the thick-walled room re-solves at Preview in under %.1f s: %s (%.1f s, %.1f x the target)\n",
              kThickResolveTargetSeconds, thick < kThickResolveTargetSeconds ? "met" : "NOT met", thick,
              thick / kThickResolveTargetSeconds);
  return 0;
}
