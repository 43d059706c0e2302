#include "trace/evaluate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "trace/parallel.h"
#include "trace/path_tracer.h"
#include "trace/replicates.h"

namespace fenestra {
namespace {

// Stream salt: evaluate draws random numbers independent of the contribution pass.
constexpr uint64_t kEvaluateStream = 0x6576616c75617465ULL;

void add_quad(Mesh* mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int material) {
  const uint32_t base = static_cast<uint32_t>(mesh->positions.size());
  mesh->positions.insert(mesh->positions.end(), {a, b, c, d});
  mesh->triangles.push_back({base, base + 1, base + 2});
  mesh->triangles.push_back({base, base + 2, base + 3});
  for (int i = 0; i < 2; ++i) {
    mesh->triangle_material.push_back(material);
    mesh->triangle_group.push_back(-1);
  }
}

}  // namespace

PanelRectangle to_panel_rectangle(const OpeningDomain& domain, const OpeningInput& opening) {
  if (!opening.parameter) return to_panel_rectangle(domain, opening.corners);
  const PanelRectangle& r = *opening.parameter;
  if (r.panel < 0 || static_cast<size_t>(r.panel) >= domain.panels().size())
    throw std::invalid_argument("is on panel " + std::to_string(r.panel) + ", which does not exist (the domain has " +
                                std::to_string(domain.panels().size()) + " panels)");
  if (!std::isfinite(r.u0) || !std::isfinite(r.u1) || !std::isfinite(r.v0) || !std::isfinite(r.v1) ||
      !(r.u1 - r.u0 > 1e-4) || !(r.v1 - r.v0 > 1e-4))
  {
    std::ostringstream m;
    m << "has parameter rectangle u " << r.u0 << ".." << r.u1 << " m, v " << r.v0 << ".." << r.v1
      << " m: expected finite numbers with u0 < u1 and v0 < v1 (meters, at least 0.1 mm apart)";
    throw std::invalid_argument(m.str());
  }
  const Panel& panel = domain.panels()[r.panel];
  constexpr double kSlack = 1e-3;  // meters: rounding of a rectangle written out and read back
  const Vec2 lo = panel.parameter_lower, hi = panel.parameter_upper;
  bool inside = r.u0 >= lo.x() - kSlack && r.u1 <= hi.x() + kSlack && r.v0 >= lo.y() - kSlack && r.v1 <= hi.y() + kSlack;
  // Points over the whole rectangle (a hair inside its edges) on the faces: a chart need not be a
  // rectangle, and a notch may cut into an edge between its corners.
  const double step = 0.5 * domain.element_size();
  const int nu = std::clamp(static_cast<int>(std::ceil(r.width() / step)), 1, 64);
  const int nv = std::clamp(static_cast<int>(std::ceil(r.height() / step)), 1, 64);
  const double du = std::min(kSlack, 0.25 * r.width()), dv = std::min(kSlack, 0.25 * r.height());
  for (int i = 0; i <= nv && inside; ++i)
    for (int j = 0; j <= nu && inside; ++j) {
      const double u = std::clamp(r.u0 + r.width() * j / nu, r.u0 + du, r.u1 - du);
      const double v = std::clamp(r.v0 + r.height() * i / nv, r.v0 + dv, r.v1 - dv);
      inside = domain.surface_at(r.panel, u, v).on_surface;
    }
  if (!inside) {
    std::ostringstream m;
    m << "has parameter rectangle u " << r.u0 << ".." << r.u1 << " m, v " << r.v0 << ".." << r.v1
      << " m, outside its panel " << r.panel << " (" << panel.label << "), whose faces span u " << lo.x() << ".."
      << hi.x() << " m, v " << lo.y() << ".." << hi.y() << " m";
    throw std::invalid_argument(m.str());
  }
  return r;
}

OpeningsGeometry build_openings(const Scene& scene, const std::vector<OpeningInput>& openings) {
  OpeningsGeometry g;
  for (size_t i = 0; i < openings.size(); ++i) {
    int panel = -1;
    Cutter box;
    try {
      if (openings[i].parameter) {
        const PanelRectangle r = to_panel_rectangle(scene.domain, openings[i]);
        panel = r.panel;
        box = scene.domain.panel_rectangle_cutter(r.panel, r.u0, r.u1, r.v0, r.v1);
      } else {
        box = scene.domain.rectangle_cutter(openings[i].corners, &panel);
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("opening " + std::to_string(i) + " " + e.what());
    }
    g.cutters.push_back(box);
    const float t = scene.domain.panels()[panel].thickness;
    if (t > 0.0f) {
      const int material = scene.domain.panels()[panel].material;
      const Vec3 back = t * box.normal;  // cutter normals point out through the wall
      const Vec3 c0 = box.origin, c1 = c0 + box.width * box.u_axis, c3 = c0 + box.height * box.v_axis;
      const Vec3 c2 = c1 + box.height * box.v_axis;
      const Vec3 ring[4] = {c0, c1, c2, c3};
      for (int e = 0; e < 4; ++e) {
        const Vec3& a = ring[e];
        const Vec3& b = ring[(e + 1) % 4];
        add_quad(&g.reveals, a, b, b + back, a + back, material);
      }
    }
  }
  return g;
}

SensorValues evaluate_openings(const Scene& scene, const std::vector<OpeningInput>& openings, Progress* progress,
                               int paths_per_sensor, SensorRange range, uint64_t stream) {
  range = range.within(scene.sensors.size());
  std::vector<size_t> sensors(range.size());
  for (size_t i = 0; i < sensors.size(); ++i) sensors[i] = range.begin + i;
  return evaluate_openings_at(scene, openings, sensors, progress, paths_per_sensor, stream);
}

SensorValues evaluate_openings_at(const Scene& scene, const std::vector<OpeningInput>& openings,
                                  const std::vector<size_t>& sensors, Progress* progress, int paths_per_sensor,
                                  uint64_t stream) {
  for (size_t s : sensors)
    if (s >= scene.sensors.size())
      throw std::invalid_argument("sensor " + std::to_string(s) + " is not one of the scene's " +
                                  std::to_string(scene.sensors.size()));
  OpeningsGeometry g = build_openings(scene, openings);
  const PathTracer tracer(scene, std::move(g.cutters), std::move(g.reveals), nullptr);
  for (size_t s : sensors) tracer.check_sensors({s, s + 1});

  const int paths = paths_per_sensor > 0 ? paths_per_sensor : scene.render.paths_per_sensor;
  const size_t tasks_per_sensor = path_tasks_per_sensor(paths);
  // Per task, its paths' sums by replicate group: stratified paths are not independent, the
  // groups are (replicates.h).
  std::vector<ReplicateSums> sums(sensors.size() * tasks_per_sensor);
  // Streams apart by an odd multiplier: their seeds differ in many bits.
  const uint64_t seed = scene.render.seed ^ kEvaluateStream ^ (stream * 0x9e3779b97f4a7c15ULL);
  if (progress) progress->start("tracing the scene with its openings", sums.size());
  parallel_path_tasks(sensors, paths, scene.render.threads, progress, [&](const PathTask& task) {
    task.for_each_path(scene.render, seed, [&](size_t p, Rng& rng, const PathSamples* samples) {
      sums[task.index].add(p, tracer.sensor_sample(task.sensor, samples, rng));
    });
  });
  SensorValues out;
  out.value.resize(static_cast<Eigen::Index>(sensors.size()));
  out.standard_error.resize(static_cast<Eigen::Index>(sensors.size()));
  for (size_t i = 0; i < sensors.size(); ++i) {
    ReplicateSums total;
    for (size_t t = 0; t < tasks_per_sensor; ++t) total.merge(sums[i * tasks_per_sensor + t]);
    total.estimate(paths, &out.value[i], &out.standard_error[i]);
  }
  return out;
}

}  // namespace fenestra
