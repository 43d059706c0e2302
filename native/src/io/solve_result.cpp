#include "io/solve_result.h"

#include <cmath>

#include "io/climate_result.h"
#include "io/results.h"

namespace fenestra {
namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
json point(const Vec3d& p) { return {p.x(), p.y(), p.z()}; }
// A position, back in the scene's input coordinates.
json position(const SiteFrame& site, const Vec3& p) { return point(site.to_site(p)); }

json error_json(const GoalError& e) {
  return {{"relative_rms", e.relative_rms}, {"max_relative", e.max_relative}, {"worst_sensor", e.worst_sensor}};
}

// The check's error and its Monte Carlo noise (a check with few paths reads worse by about it).
json verified_error_json(const SolveResult& r) {
  json e = error_json(r.verified_error);
  e["noise_rms"] = goal_noise(r.goals, r.verified_stderr);
  return e;
}

json openings_json(const SiteFrame& site, const std::vector<OpeningRectangle>& openings) {
  json list = json::array();
  for (const OpeningRectangle& o : openings) {
    json corners = json::array();
    for (const Vec3& c : o.corners) corners.push_back(position(site, c));
    json entry = {{"corners", corners},
                  {"centre", position(site, o.centre)},
                  {"width", o.width},
                  {"height", o.height},
                  {"normal", point(o.outward)},
                  {"depth", o.depth},
                  {"panel", o.panel},
                  {"parameter_rectangle",
                   {{"u0", o.parameter.u0}, {"u1", o.parameter.u1}, {"v0", o.parameter.v0}, {"v1", o.parameter.v1}}},
                  {"curved", o.curved},
                  {"rows", {o.row0, o.row1}},
                  {"columns", {o.col0, o.col1}},
                  {"elements", o.elements}};
    if (o.curved) {
      json points = json::array(), normals = json::array();
      for (const Vec3& p : o.grid_points) points.push_back(position(site, p));
      for (const Vec3& n : o.grid_normals) normals.push_back(point(n));
      entry["surface_grid"] = {{"rows", o.grid_rows}, {"columns", o.grid_columns}, {"points", points}, {"normals", normals}};
    }
    list.push_back(entry);
  }
  return list;
}

json tradeoffs_json(const Scene& scene, const SolveResult& r) {
  json list = json::array();
  for (const TradeoffResult& t : r.tradeoffs) {
    double area = 0.0;
    for (const OpeningRectangle& o : t.openings) area += o.width * o.height;
    json climate = nullptr;
    if (!t.climate.empty()) {
      json figures = json::array(), goals_met = json::array();
      bool met = true;
      for (size_t g = 0; g < t.climate.size(); ++g) {
        figures.push_back(t.climate[g].achieved);
        goals_met.push_back(figure_meets(scene.sensors.climate_goals.goals[g], t.climate[g].achieved));
        met = met && goals_met.back().get<bool>();
      }
      climate = {{"achieved", figures}, {"met", goals_met}, {"all_met", met},
                 {"figures_by", t.climate_cut ? "cutters" : "records"}};
    }
    list.push_back({{"climate", climate},{"openings_count", t.openings.size()},
                    {"answer", t.answer},
                    {"glazing_area_m2", area},
                    {"error", error_json(t.error)},
                    {"predicted_by", t.cut ? "cutters" : "records"},
                    {"openings", openings_json(scene.site, t.openings)},
                    {"predicted", std::vector<double>(t.predicted.data(), t.predicted.data() + t.predicted.size())},
                    {"predicted_stderr", std::vector<double>(t.predicted_stderr.data(),
                                                             t.predicted_stderr.data() + t.predicted_stderr.size())}});
  }
  return list;
}

json open_list(const std::vector<uint8_t>& open) {
  json list = json::array();
  for (size_t k = 0; k < open.size(); ++k)
    if (open[k]) list.push_back(k);
  return list;
}

json sensors_json(const SolveResult& r) {
  json list = json::array();
  for (Eigen::Index i = 0; i < r.predicted.size(); ++i) {
    const bool has_goal = r.goals.weight[i] > 0.0;
    list.push_back({{"goal", has_goal ? number_or_null(r.goals.target[i]) : json(nullptr)},
                    {"goal_as_given", number_or_null(r.goals.given[i])},
                    {"min", has_goal ? number_or_null(r.goals.lower[i]) : json(nullptr)},
                    {"max", has_goal ? number_or_null(r.goals.upper[i]) : json(nullptr)},
                    {"weight", r.goals.weight[i]},
                    {"predicted", r.predicted[i]},
                    {"predicted_stderr", r.predicted_stderr[i]},
                    {"linear", r.linear[i]},
                    {"compensated", r.compensated[i]}});
    if (r.verified) {
      list.back()["verified"] = r.verified_value[i];
      list.back()["verified_stderr"] = r.verified_stderr[i];
    }
  }
  return list;
}

}  // namespace

json constraints_json(const OpeningConstraints& c) {
  json j = json::object();
  const std::pair<const char*, double> values[] = {
      {"min_area", c.min_area},     {"max_area", c.max_area},     {"min_aspect", c.min_aspect},
      {"max_aspect", c.max_aspect}, {"min_width", c.min_width},   {"max_width", c.max_width},
      {"min_height", c.min_height}, {"max_height", c.max_height}, {"min_gap", c.min_gap},
      {"margin", c.margin},         {"sill_min", c.sill_min},     {"sill_max", c.sill_max},
      {"head_min", c.head_min},     {"head_max", c.head_max},     {"module", c.module},
      {"head_clearance", c.head_clearance}, {"panel_width_per_opening", c.panel_width_per_opening}};
  for (const auto& [name, value] : values)
    if (std::isfinite(value) && value > 0.0) j[name] = value;  // only what constrains
  if (c.max_openings > 0) j["max_openings"] = c.max_openings;
  if (c.max_openings_per_panel > 0) j["max_openings_per_panel"] = c.max_openings_per_panel;
  if (!c.catalogue.empty()) j["catalogue"] = c.catalogue.name;
  const std::pair<const char*, bool> rules[] = {{"align_sills", c.align_sills},   {"align_heads", c.align_heads},
                                                {"equal_widths", c.equal_widths}, {"same_type_in_row", c.same_type_in_row},
                                                {"symmetric", c.symmetric},       {"equal_spacing", c.equal_spacing}};
  for (const auto& [name, on] : rules)
    if (on) j[name] = true;
  if (c.automatic_alignment) j["automatic_alignment"] = true;  // align_* automatic: kept where cheap
  if (!c.sill_heights.empty()) j["sill_heights"] = c.sill_heights;
  j["automatic"] = c.automatic_keys;  // the keys above that took their automatic value
  return j;
}

json solve_result_json(const Scene& scene, const SolveResult& r) {
  json history = json::array();
  for (const GenerationRecord& g : r.history)
    history.push_back({{"generation", g.generation}, {"best", g.best}, {"mean", g.mean}, {"seconds", g.seconds}});
  json timings = json::object();
  for (const auto& t : r.timings) timings[t.stage] = t.seconds;
  json stages = json::array();
  for (const SolveStage& st : r.stages) {
    json stage = {{"name", st.name}, {"seconds", st.seconds}, {"stopped_because", st.stopped_because}};
    if (std::isfinite(st.error_before) && std::isfinite(st.error_after)) {
      stage["error_before"] = st.error_before;
      stage["error_after"] = st.error_after;
    }
    stages.push_back(std::move(stage));
  }
  const SolverSettings& s = scene.solver;
  json out = {
      {"units", "sensor values: luminance-weighted irradiance, lux for a sky in cd/m^2; corners in meters"},
      {"goal_units", scene.sensors.goal_units},
      {"openings", openings_json(scene.site, r.openings)},
      {"open_elements", open_list(r.open)},
      {"element_count", r.open.size()},
      {"element_size", scene.domain.element_size()},
      {"sensors", sensors_json(r)},
      {"error", {{"relative_rms", r.error.relative_rms},
                 {"max_relative", r.error.max_relative},
                 {"worst_sensor", r.error.worst_sensor},
                 {"linear", error_json(r.linear_error)},
                 {"compensated", error_json(r.compensated_error)},
                 {"start", error_json(r.start_error)},
                 {"before_constraints", error_json(r.unconstrained_error)},
                 {"refined", error_json(r.refined_error)},
                 {"verified", r.verified ? verified_error_json(r) : json(nullptr)},
                 {"nnls_relative_rms", r.nnls_relative_rms}}},
      {"fitness", r.fitness},
      {"warnings", r.warnings},
      {"dropped", dropped_json(r.dropped)},
      {"constraints_met", r.constraint_violations.empty()},
      {"tradeoffs", tradeoffs_json(scene, r)},
      {"composition", [&] {
         json steps = json::array();
         for (const CompositionStep& c : r.composition)
           steps.push_back({{"rule", c.rule}, {"met", c.met}, {"error_before", c.error_before},
                            {"error_after", c.error_after}, {"automatic", c.automatic}, {"kept", c.kept}});
         return steps;
       }()},
      {"constraint_violations", r.constraint_violations},
      {"unconstrained", {{"open_elements", open_list(r.unconstrained_open)},
                         {"openings", openings_json(scene.site, r.unconstrained_openings)},
                         {"error", error_json(r.unconstrained_error)}}},
      {"timings_s", timings},
      {"stages", stages},
      {"genetic", {{"generations", r.generations}, {"coarse_factors", r.coarse_factors}, {"history", history}}},
      {"edge_moves", r.edge_moves},
      {"second_start", {{"run", r.second_start}, {"kept", r.second_start_kept}}},
      {"opening_search", {{"run", r.opening_search.ran},
                          {"starts", r.opening_search.starts},
                          {"best_start", r.opening_search.best_start},
                          {"evaluations", r.opening_search.evaluations},
                          {"scored", r.opening_search.scored},
                          {"best_found_after", r.opening_search.best_found_after},
                          {"moves", r.opening_search.moves},
                          {"restarts", r.opening_search.restarts},
                          {"pair_moves", r.opening_search.pair_moves},
                          {"alternatives_kept", r.opening_search.alternatives_kept},
                          {"kept", r.opening_search.kept}}},
      {"thick_wall_openings", {{"run", r.thick_wall_openings.ran},
                               {"evaluations", r.thick_wall_openings.evaluations},
                               {"moves", r.thick_wall_openings.moves},
                               {"interpolated_before", r.thick_wall_openings.interpolated_before},
                               {"interpolated_after", r.thick_wall_openings.interpolated_after},
                               {"kept", r.thick_wall_openings.kept},
                               {"reverted", r.thick_wall_openings.reverted}}},
      {"thick_wall_edges", {{"run", r.thick_wall_edges.ran},
                            {"searched", r.thick_wall_edges.searched},
                            {"cuts", r.thick_wall_edges.cuts},
                            {"paths_per_cut", r.thick_wall_edges.paths_per_cut},
                            {"rough_cuts", r.thick_wall_edges.rough_cuts},
                            {"moves", r.thick_wall_edges.moves},
                            {"from_placement", r.thick_wall_edges.from_placement}}},
      {"thick_wall_merges", {{"run", r.thick_wall_merges.ran},
                             {"cuts", r.thick_wall_merges.cuts},
                             {"rough_cuts", r.thick_wall_merges.rough_cuts},
                             {"removed", r.thick_wall_merges.removed},
                             {"merged", r.thick_wall_merges.merged},
                             {"merges_searched", r.thick_wall_merges.merges_searched},
                             {"traced_share", r.thick_wall_merges.traced_share}}},
      {"thick_wall_joint_edges", {{"run", r.thick_wall_joint_edges.ran},
                                  {"steps", r.thick_wall_joint_edges.steps},
                                  {"sides", r.thick_wall_joint_edges.sides},
                                  {"cuts", r.thick_wall_joint_edges.cuts},
                                  {"judged_cuts", r.thick_wall_joint_edges.judged_cuts},
                                  {"paths_per_cut", r.thick_wall_joint_edges.paths_per_cut},
                                  {"judge_paths", r.thick_wall_joint_edges.judge_paths},
                                  {"scanned", r.thick_wall_joint_edges.scanned},
                                  {"scan_cuts", r.thick_wall_joint_edges.scan_cuts},
                                  {"scan_rough_cuts", r.thick_wall_joint_edges.scan_rough_cuts},
                                  {"scan_moves", r.thick_wall_joint_edges.scan_moves},
                                  {"traced_share", r.thick_wall_joint_edges.traced_share}}},
      {"constraint_costs", [&] {
         json costs = json::array();
         for (const ConstraintCost& c : r.constraint_costs)
           costs.push_back({{"keys", c.keys}, {"error_without", c.error_without}});
         return costs;
       }()},
      {"settings", {{"paths_per_sensor", s.paths_per_sensor > 0 ? s.paths_per_sensor : scene.render.paths_per_sensor},
                    {"population", s.population},
                    {"generations", s.generations},
                    {"seed", s.seed},
                    {"time_budget_s", s.time_budget_s},
                    {"coarse_to_fine", s.coarse_to_fine},
                    {"shape_weights", {{"isolated", s.isolated_weight}, {"boundary", s.boundary_weight},
                                       {"regions", s.regions_weight}}},
                    {"bound_weight", s.bound_weight},
                    {"constraints", constraints_json(s.constraints)},
                    {"panel_constraints", [&] {
                       json per_panel = json::array();
                       for (const OpeningConstraints& set : s.constraints.per_panel)
                         per_panel.push_back(constraints_json(set));
                       return per_panel;
                     }()},
                    {"improve_iterations", s.improve_iterations},
                    {"search_evaluations", s.search_evaluations},
                    {"refine_edges", s.refine_edges},
                    {"verify", s.verify},
                    {"verify_paths", s.verify_paths},
                    {"tradeoffs", s.tradeoffs}}}};
  if (r.climate.active) out["climate"] = climate_result_json(scene, r.climate);
  return out;
}

}  // namespace fenestra
