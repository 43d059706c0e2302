#include "scene/settings_input.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "scene/input_limits.h"
#include "util/quoted_text.h"

namespace fenestra {

using namespace scene_json;  // the path-aware readers

SolverSettings parse_solver(const ScenePath& sp, const json& j) {
  SolverSettings s;
  if (j.is_null()) return s;
  if (!j.is_object()) sp.fail("solver", "expected an object");
  check_known_keys(sp, j, "solver",
                   {"element_size", "paths", "population", "generations", "seed", "time_budget_s", "shape_weights",
                    "bound_weight", "coarse_to_fine", "elite", "constraints", "panel_constraints", "improve_iterations",
                    "search_evaluations", "verify", "verify_paths", "refine_edges", "tradeoffs"});
  auto integer = [&](const char* name, int lo, int hi, int fallback) {
    if (!j.contains(name)) return fallback;
    const double v = number(sp, j.at(name), std::string("solver.") + name);
    if (v != std::floor(v) || v < lo || v > hi)
      sp.fail(std::string("solver.") + name,
              "expected a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
  };
  s.paths_per_sensor = integer("paths", 1, 1 << 24, 0);
  s.population = integer("population", 4, 100000, s.population);
  s.generations = integer("generations", 0, 10000000, s.generations);
  s.elite = integer("elite", 1, 1000, s.elite);
  if (j.contains("seed")) s.seed = static_cast<uint64_t>(integer("seed", 0, 2147483647, 1));
  s.time_budget_s = number_or(sp, j, "time_budget_s", "solver", 0.0);
  if (s.time_budget_s < 0.0) sp.fail("solver.time_budget_s", "must not be negative");
  s.bound_weight = number_or(sp, j, "bound_weight", "solver", s.bound_weight);
  if (s.bound_weight < 0.0) sp.fail("solver.bound_weight", "must not be negative");
  if (j.contains("coarse_to_fine")) {
    if (!j.at("coarse_to_fine").is_boolean()) sp.fail("solver.coarse_to_fine", "expected true or false");
    s.coarse_to_fine = j.at("coarse_to_fine").get<bool>();
  }
  s.improve_iterations = integer("improve_iterations", 0, 100000000, s.improve_iterations);
  s.search_evaluations = integer("search_evaluations", 0, 10000000, s.search_evaluations);
  if (j.contains("refine_edges")) {
    if (!j.at("refine_edges").is_boolean()) sp.fail("solver.refine_edges", "expected true or false");
    s.refine_edges = j.at("refine_edges").get<bool>();
  }
  if (j.contains("verify")) {
    if (!j.at("verify").is_boolean()) sp.fail("solver.verify", "expected true or false");
    s.verify = j.at("verify").get<bool>();
  }
  s.verify_paths = integer("verify_paths", 0, 1 << 24, s.verify_paths);
  if (j.contains("tradeoffs")) {
    if (!j.at("tradeoffs").is_boolean()) sp.fail("solver.tradeoffs", "expected true or false");
    s.tradeoffs = j.at("tradeoffs").get<bool>();
  }
  if (j.contains("shape_weights")) {
    const json& w = j.at("shape_weights");
    if (!w.is_object()) sp.fail("solver.shape_weights", "expected {\"isolated\", \"boundary\", \"regions\"}");
    check_known_keys(sp, w, "solver.shape_weights", {"isolated", "boundary", "regions"});
    s.isolated_weight = number_or(sp, w, "isolated", "solver.shape_weights", s.isolated_weight);
    s.boundary_weight = number_or(sp, w, "boundary", "solver.shape_weights", s.boundary_weight);
    s.regions_weight = number_or(sp, w, "regions", "solver.shape_weights", s.regions_weight);
    if (s.isolated_weight < 0 || s.boundary_weight < 0 || s.regions_weight < 0)
      sp.fail("solver.shape_weights", "weights must not be negative");
  }
  return s;
}

RenderSettings parse_render(const ScenePath& sp, const json& j) {
  RenderSettings r;
  if (j.is_null()) return r;
  if (!j.is_object()) sp.fail("render", "expected an object");
  check_known_keys(sp, j, "render", {"paths_per_sensor", "max_bounces", "seed", "threads", "sampler"});
  auto integer = [&](const IntegerRange& range, long long fallback) {
    const std::string name = std::string(range.key).substr(std::string("render.").size());
    return j.contains(name) ? integer_in(sp, j.at(name), range, range.key) : fallback;
  };
  r.paths_per_sensor = static_cast<int>(integer(limits::kPathsPerSensor, r.paths_per_sensor));
  r.max_bounces = static_cast<int>(integer(limits::kMaxBounces, r.max_bounces));
  r.seed = static_cast<uint64_t>(integer(limits::kSeed, 1));
  r.threads = static_cast<int>(integer(limits::kThreads, 0));
  if (j.contains("sampler")) {
    const json& v = j.at("sampler");
    if (!v.is_string() || !parse_sampler(v.get<std::string>(), &r.sampler))
      sp.fail("render.sampler", "expected \"sobol\" or \"independent\", got " + quoted_json(v));
  }
  return r;
}

}  // namespace fenestra
