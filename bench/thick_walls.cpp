#include "thick_walls.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>
#include <utility>
#include <vector>

#include "annual/annual_contributions.h"
#include "trace/contributions.h"
#include "trace/ray_scene.h"
#include "trace/evaluate.h"

namespace bench {

namespace {

constexpr int kWallPaths = 2048;
constexpr float kWallThickness = 0.3f;  // meters

struct WallCost {
  double seconds = 0.0;
  size_t record_bytes = 0;
  double relative_variance = 0.0;  // mean over sensors and open sets of (standard error / value)^2
  std::array<double, 3> set_variance{};  // the same, per open set (all open, random half, bands)
  double rays_per_path = 0.0;
};

// All open, a random half, bands of four in ten.
std::vector<std::vector<uint8_t>> wall_open_sets(size_t n) {
  std::vector<std::vector<uint8_t>> sets(3, std::vector<uint8_t>(n, 0));
  std::mt19937 rng(5);
  for (size_t k = 0; k < n; ++k) sets[0][k] = 1, sets[1][k] = rng() % 2, sets[2][k] = k % 10 < 4;
  return sets;
}

// One pass, and the run's own noise on the exact values of a few open sets (all open, half, a band).
WallCost wall_cost(const Scene& base) {
  const Scene scene = with_paths(base, kWallPaths, kReferenceSeed + 7);
  const uint64_t rays_before = fenestra::rays_traced();
  const auto start = Clock::now();
  const fenestra::Contributions c = fenestra::compute_contributions(scene);
  WallCost cost;
  cost.seconds = seconds_since(start);
  cost.rays_per_path = static_cast<double>(fenestra::rays_traced() - rays_before) /
                       static_cast<double>(kWallPaths * scene.sensors.size());
  for (const auto& r : c.records) cost.record_bytes += r.memory_bytes();
  const std::vector<std::vector<uint8_t>> sets = wall_open_sets(c.element_count());
  size_t count = 0;
  for (size_t s = 0; s < sets.size(); ++s) {
    const fenestra::SensorValues v = c.evaluate(sets[s]);
    size_t set_count = 0;
    for (Eigen::Index i = 0; i < v.value.size(); ++i) {
      if (!(v.value[i] > 0.0)) continue;
      const double r = std::pow(v.standard_error[i] / v.value[i], 2);
      cost.relative_variance += r, cost.set_variance[s] += r, ++count, ++set_count;
    }
    cost.set_variance[s] /= std::max<size_t>(1, set_count);
  }
  cost.relative_variance /= std::max<size_t>(1, count);
  return cost;
}

json wall_cost_json(const WallCost& w) {
  return {{"seconds", w.seconds},
          {"record_bytes", w.record_bytes},
          {"rays_per_path", w.rays_per_path},
          {"relative_variance", w.relative_variance},
          {"relative_variance_per_set", {{"all_open", w.set_variance[0]}, {"random_half", w.set_variance[1]},
                                         {"bands", w.set_variance[2]}}}};
}

// What the wall's light costs a forward path tracer: `evaluate` with the same open sets really cut
// (one opening per open element), seconds x mean relative variance over the sets.
constexpr int kForwardPaths = 256;

double forward_cost(const Scene& base) {
  const Scene scene = with_paths(base, kForwardPaths, kReferenceSeed + 11);
  double seconds = 0.0, variance = 0.0;
  size_t count = 0;
  for (const auto& open : wall_open_sets(scene.domain.element_count())) {
    std::vector<fenestra::OpeningInput> openings;
    for (size_t k = 0; k < open.size(); ++k)
      if (open[k]) {
        const fenestra::Element& e = scene.domain.elements()[k];
        openings.push_back(fenestra::PanelRectangle{e.panel, e.u0, e.u1, e.v0, e.v1});
      }
    const auto start = Clock::now();
    const fenestra::SensorValues v = fenestra::evaluate_openings(scene, openings);
    seconds += seconds_since(start);
    for (Eigen::Index i = 0; i < v.value.size(); ++i)
      if (v.value[i] > 0.0) variance += std::pow(v.standard_error[i] / v.value[i], 2), ++count;
  }
  return seconds * variance / std::max<size_t>(1, count);
}

}  // namespace

json thick_wall_comparison(const std::string& scene_path) {
  std::ifstream in(scene_path);
  json text = json::parse(in);
  text["opening_domain"]["thickness"] = kWallThickness;
  const std::string dir = scene_path.substr(0, scene_path.find_last_of('/'));
  const Scene thick = fenestra::parse_scene(text.dump(), dir, scene_path + " (0.3 m walls)");
  text["opening_domain"]["thickness"] = 0.0;
  const Scene thin = fenestra::parse_scene(text.dump(), dir, scene_path);
  const WallCost a = wall_cost(thin), b = wall_cost(thick);
  const double time_ratio = (b.seconds * b.relative_variance) / (a.seconds * a.relative_variance);
  const double memory_ratio = static_cast<double>(b.record_bytes) / static_cast<double>(a.record_bytes);
  std::printf("[5] Thick walls: the domain as a %.1f m wall against the zero-thickness one, %d paths per sensor\n"
              "    %-8s %9s %12s %10s %14s  %s\n", kWallThickness, kWallPaths, "wall", "seconds", "records MiB",
              "rays/path", "rel. variance", "(all open, random half, bands)");
  for (const auto& [name, w] : {std::pair<const char*, const WallCost&>{"thin", a}, {"0.3 m", b}})
    std::printf("    %-8s %9.2f %12.1f %10.1f %14.3g  (%.3g, %.3g, %.3g)\n", name, w.seconds, mib(w.record_bytes),
                w.rays_per_path, w.relative_variance, w.set_variance[0], w.set_variance[1], w.set_variance[2]);
  std::printf("    time to the same accuracy (seconds x relative variance): %.2f x the thin wall's; path-record "
              "memory %.2f x\n", time_ratio, memory_ratio);
  const double forward_ratio = forward_cost(thick) / forward_cost(thin);
  std::printf("    the same sets really cut (evaluate, %d paths): time to the same accuracy %.2f x the thin wall's\n\n",
              kForwardPaths, forward_ratio);
  return {{"paths", kWallPaths},
          {"thickness_m", kWallThickness},
          {"thin", wall_cost_json(a)},
          {"thick", wall_cost_json(b)},
          {"time_to_accuracy_ratio", time_ratio},
          {"forward_time_to_accuracy_ratio", forward_ratio},
          {"record_memory_ratio", memory_ratio}};
}

}  // namespace bench
