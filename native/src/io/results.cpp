#include "io/results.h"

#include <cmath>
#include <functional>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "format/atomic_file.h"
#include "format/json_input.h"
#include "format/json_keys.h"
#include "format/npz_writer.h"
#include "format/output_pair.h"
#include "scene/input_limits.h"
#include "trace/contributions_origin.h"
#include "util/out_of_memory.h"
#include "util/quoted_text.h"
#include "util/whole_file.h"

namespace fenestra {

using nlohmann::json;

namespace {

std::vector<double> row_major(const Eigen::MatrixXd& m) {
  std::vector<double> out(static_cast<size_t>(m.size()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out[static_cast<size_t>(i * m.cols() + j)] = m(i, j);
  return out;
}

std::vector<double> to_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

json vec_json(const Vec3& p) { return json::array({p.x(), p.y(), p.z()}); }
json vec_json(const Vec3d& p) { return json::array({p.x(), p.y(), p.z()}); }

}  // namespace

json dropped_json(const DropCounts& d) {
  return {{"non_finite", d.non_finite}, {"truncated_conditions", d.truncated_conditions}};
}

json elements_json(const Scene& scene) {
  json list = json::array();
  const auto& elements = scene.domain.elements();
  for (size_t k = 0; k < elements.size(); ++k) {
    const Element& e = elements[k];
    json corners = json::array();
    for (const auto& c : e.corners) corners.push_back(vec_json(scene.site.to_site(c)));
    list.push_back({{"index", k}, {"panel", e.panel}, {"row", e.row}, {"col", e.col}, {"corners", corners}});
  }
  return list;
}

std::pair<std::string, std::string> write_contributions(const Scene& scene, const Contributions& c,
                                                        const std::string& out) {
  const auto [npz_path, json_path] = npz_json_pair(out);
  check_output_paths({npz_path, json_path}, scene.input_files);  // before the arrays are copied
  check_contributions_match(scene, c, "saving '" + quoted_path(npz_path) + "'");

  const size_t ns = c.sensor_count(), no = c.element_count();
  NpzWriter npz;
  npz.add("E", row_major(c.E), {ns, no});
  npz.add("E_stderr", row_major(c.E_stderr), {ns, no});
  npz.add("A", row_major(c.A), {ns, no});
  npz.add("T", row_major(c.T), {no, no});
  npz.add("closed", to_vector(c.closed.value), {ns});
  npz.add("closed_stderr", to_vector(c.closed.standard_error), {ns});
  npz.add("all_open", to_vector(c.all_open.value), {ns});
  npz.add("all_open_stderr", to_vector(c.all_open.standard_error), {ns});
  std::vector<int32_t> panel, row, col;
  std::vector<double> corners;
  for (const auto& e : scene.domain.elements()) {
    panel.push_back(e.panel), row.push_back(e.row), col.push_back(e.col);
    for (const auto& c : e.corners) {
      const Vec3d p = scene.site.to_site(c);
      corners.insert(corners.end(), {p.x(), p.y(), p.z()});
    }
  }
  npz.add("element_panel", panel, {no});
  npz.add("element_row", row, {no});
  npz.add("element_col", col, {no});
  npz.add("element_corners", corners, {no, 4, 3});

  json panels = json::array();
  for (const auto& p : scene.domain.panels())
    panels.push_back({{"label", p.label}, {"rows", p.rows}, {"cols", p.cols}, {"area_m2", p.area},
                      {"origin", vec_json(scene.site.to_site(p.origin))}, {"u_axis", vec_json(p.u_axis)}, {"v_axis", vec_json(p.v_axis)},
                      {"normal", vec_json(p.normal)}, {"outward", vec_json(p.outward)},
                      {"parameterisation", p.curved() ? p.chart->source_name() : "plane"},
                      {"parameter_domain", {{"u0", p.parameter_lower.x()}, {"u1", p.parameter_upper.x()},
                                            {"v0", p.parameter_lower.y()}, {"v1", p.parameter_upper.y()}}}});
  json summary = {
      {"format", "fenestra-contributions"},
      {"version", 1},
      {"scene", scene.source},
      {"arrays", npz_path},
      {"units", "luminance-weighted irradiance: lux for a sky in cd/m^2"},
      {"sensors", ns},
      {"element_count", no},
      {"element_size_m", scene.domain.element_size()},
      {"paths_per_sensor", c.paths_per_sensor},
      {"seconds", c.seconds},
      {"closed", to_vector(c.closed.value)},
      {"all_open", to_vector(c.all_open.value)},
      {"panels", panels},
      {"elements", elements_json(scene)},
      {"warnings", c.warnings},
      {"dropped", dropped_json(c.dropped)},
  };
  // The pair appears together or not at all (format/atomic_file.h); the summary, which names the
  // arrays, is renamed into place last.
  write_files_atomically(
      {{npz_path, [&](std::ostream& o) { npz.write(o); }},
       {json_path, [&](std::ostream& o) { o << summary.dump(2, ' ', false, json::error_handler_t::replace) << "\n"; }}},
      scene.input_files);
  return {npz_path, json_path};
}

namespace {

// "panel": i, "parameter_rectangle": {"u0", "u1", "v0", "v1"} (meters in the panel's parameter domain).
PanelRectangle parse_parameter_rectangle(const json& o, const std::function<void(const std::string&)>& fail) {
  if (!o.contains("panel") || !o.at("panel").is_number_integer() || o.at("panel").get<int64_t>() < 0 ||
      o.at("panel").get<int64_t>() > 1000000000)
    fail("\"parameter_rectangle\" needs \"panel\": the index of its panel (a whole number >= 0)");
  const json& r = o.at("parameter_rectangle");
  if (!r.is_object()) fail("\"parameter_rectangle\" is not an object {\"u0\", \"u1\", \"v0\", \"v1\"}");
  if (const auto unknown = find_unknown_key(r, {"u0", "u1", "v0", "v1"}))
    fail("parameter_rectangle." + quoted_text(unknown->key) + ": " + unknown->message);
  PanelRectangle out;
  out.panel = static_cast<int>(o.at("panel").get<int64_t>());
  double* fields[] = {&out.u0, &out.u1, &out.v0, &out.v1};
  const char* names[] = {"u0", "u1", "v0", "v1"};
  for (int i = 0; i < 4; ++i) {
    if (!r.contains(names[i]) || !r.at(names[i]).is_number())
      fail(std::string("\"parameter_rectangle\" has no number \"") + names[i] + "\" (meters)");
    *fields[i] = r.at(names[i]).get<double>();
    if (!std::isfinite(*fields[i]) || std::abs(*fields[i]) > 1e6)
      fail(std::string("\"parameter_rectangle\" ") + names[i] + " is not a finite number of meters within 1e6");
  }
  return out;
}

}  // namespace

std::vector<OpeningInput> parse_openings(const json& j, const std::string& source, const SiteFrame& frame) {
  auto fail = [&](const std::string& m) -> void {
    throw std::invalid_argument("openings '" + quoted_text(source) + "': " + m);
  };
  // An openings file, or a solve's result (docs/solver.md), whose other keys are read past.
  if (const auto unknown = find_unknown_key(j, {"openings", "units", "goal_units", "open_elements", "element_count",
                                               "element_size", "sensors", "error", "fitness", "warnings", "dropped",
                                               "constraints_met", "tradeoffs", "composition",
                                               "constraint_violations", "unconstrained", "timings_s", "stages", "genetic",
                                               "edge_moves", "second_start", "opening_search", "thick_wall_openings", "thick_wall_edges", "thick_wall_merges", "thick_wall_joint_edges",
                                               "constraint_costs", "settings",
                                               "climate"}))
    fail(quoted_text(unknown->key) + ": " + unknown->message);
  if (!j.is_object() || !j.contains("openings") || !j.at("openings").is_array())
    fail("expected an object with an \"openings\" list");
  std::vector<OpeningInput> out;
  const json& list = j.at("openings");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = "opening " + std::to_string(i);
    const json& o = list[i];
    // "corners" or "panel" and "parameter_rectangle"; the rest describe a solve's opening.
    if (const auto unknown = find_unknown_key(o, {"corners", "panel", "parameter_rectangle", "centre", "width",
                                                 "height", "normal", "depth", "curved", "rows", "columns",
                                                 "elements", "surface_grid"}))
      fail(where + ": " + quoted_text(unknown->key) + ": " + unknown->message);
    if (o.is_object() && o.contains("parameter_rectangle")) {
      out.emplace_back(parse_parameter_rectangle(o, [&](const std::string& m) { fail(where + ": " + m); }));
      continue;
    }
    if (!o.is_object() || !o.contains("corners") || !o.at("corners").is_array() || o.at("corners").size() != 4)
      fail(where + ": expected \"corners\": four [x, y, z] points, or \"panel\" and \"parameter_rectangle\"");
    Rectangle r;
    for (int c = 0; c < 4; ++c) {
      const json& p = o.at("corners")[c];
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
        fail(where + ": corner " + std::to_string(c) + " is not [x, y, z]");
      for (int k = 0; k < 3; ++k)
        if (!coordinate_in_range(p[k].get<double>()))
          fail(where + ": corner " + std::to_string(c) + " " + quoted_json(p) + " is out of range: coordinates " +
               coordinate_requirement());
      const Vec3d site(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      if (!local_coordinates_in_range(frame.to_local_exact(site)))
        fail(where + ": corner " + std::to_string(c) + " " + quoted_json(p) + " " + local_range_problem(frame.origin));
      r[c] = frame.to_local(site);
    }
    out.emplace_back(r);
  }
  return out;
}

namespace {

json openings_file_json(const std::string& path) {
  check_input_file(path, "openings file", limits::kMaxSceneFileBytes);
  return out_of_memory_while("reading openings file '" + quoted_path(path) + "'",
                             [&] { return parse_json_text(read_whole_file(path, "openings file"), "openings", path); });
}

}  // namespace

namespace {

// A frame around the corners an openings file gives (SiteFrame::around), the origin if none.
SiteFrame frame_of_corners(const json& j) {
  bool any = false;
  Vec3d lo, hi;
  if (j.is_object() && j.contains("openings") && j.at("openings").is_array())
    for (const json& o : j.at("openings"))
      if (o.is_object() && o.contains("corners") && o.at("corners").is_array())
        for (const json& p : o.at("corners"))
          if (p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() && p[2].is_number()) {
            const Vec3d v(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
            if (!v.allFinite()) continue;
            lo = any ? lo.cwiseMin(v) : v, hi = any ? hi.cwiseMax(v) : v, any = true;
          }
  return any ? SiteFrame::around(lo, hi) : SiteFrame{};
}

std::vector<OpeningInput> openings_of(const json& j, const std::string& path, const SiteFrame& frame) {
  try {
    return parse_openings(j, path, frame);
  } catch (const json::exception& e) {
    throw std::invalid_argument("openings '" + quoted_path(path) + "': a value has the wrong type: " + json_error_text(e));
  }
}

}  // namespace

std::vector<OpeningInput> read_openings(const std::string& path, const SiteFrame& frame) {
  return openings_of(openings_file_json(path), path, frame);
}

std::vector<OpeningInput> read_openings_in_own_frame(const std::string& path, SiteFrame* frame) {
  const json j = openings_file_json(path);
  *frame = frame_of_corners(j);
  return openings_of(j, path, *frame);
}

json evaluation_json(const SensorValues& values, size_t openings, int paths_per_sensor,
                     double horizontal_illuminance, const std::vector<std::string>& warnings) {
  json sensors = json::array();
  for (Eigen::Index i = 0; i < values.value.size(); ++i) {
    json s = {{"value", values.value[i]}, {"stderr", values.standard_error[i]}};
    // Daylight factor: percent of what an unobstructed horizontal surface receives from the same sky.
    if (horizontal_illuminance > 0.0) s["daylight_factor"] = 100.0 * values.value[i] / horizontal_illuminance;
    sensors.push_back(std::move(s));
  }
  return {{"units", "luminance-weighted irradiance: lux for a sky in cd/m^2"},
          {"openings", openings},
          {"paths_per_sensor", paths_per_sensor},
          {"horizontal_illuminance", horizontal_illuminance},
          {"sensors", sensors},
          {"warnings", warnings}};
}

void write_json(const std::string& path, const json& j) {
  // Text that is not UTF-8 (a file name) is written with replacement characters rather than refused.
  write_atomically(path, [&](std::ostream& o) { o << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n"; });
}

}  // namespace fenestra
