#include "trace/evaluate.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "trace/parallel.h"
#include "trace/path_tracer.h"

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

OpeningsGeometry build_openings(const Scene& scene, const std::vector<Rectangle>& openings) {
  OpeningsGeometry g;
  for (size_t i = 0; i < openings.size(); ++i) {
    int panel = -1;
    CutterBox box;
    try {
      box = scene.domain.rectangle_cutter(openings[i], &panel);
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

SensorValues evaluate_openings(const Scene& scene, const std::vector<Rectangle>& openings, Progress* progress) {
  OpeningsGeometry g = build_openings(scene, openings);
  const PathTracer tracer(scene, std::move(g.cutters), std::move(g.reveals));
  tracer.check_sensors();

  const size_t sensors = scene.sensors.size();
  const int paths = scene.render.paths_per_sensor;
  const size_t tasks_per_sensor = (paths + kPathsPerTask - 1) / kPathsPerTask;
  std::vector<double> sum(sensors * tasks_per_sensor, 0.0), sum_sq(sensors * tasks_per_sensor, 0.0);
  if (progress) progress->start("tracing the scene with its openings", sum.size());
  parallel_tasks(sum.size(), scene.render.threads, progress, [&](size_t task) {
    const size_t sensor = task / tasks_per_sensor;
    const size_t first = (task % tasks_per_sensor) * kPathsPerTask;
    const size_t last = std::min<size_t>(paths, first + kPathsPerTask);
    for (size_t p = first; p < last; ++p) {
      Rng rng = path_rng(scene.render.seed ^ kEvaluateStream, sensor, p);
      const double v = tracer.sensor_sample(sensor, rng);
      sum[task] += v;
      sum_sq[task] += v * v;
    }
  });
  SensorValues out;
  out.value.resize(sensors);
  out.standard_error.resize(sensors);
  for (size_t i = 0; i < sensors; ++i) {
    double s = 0.0, s2 = 0.0;
    for (size_t t = 0; t < tasks_per_sensor; ++t) s += sum[i * tasks_per_sensor + t], s2 += sum_sq[i * tasks_per_sensor + t];
    const double n = paths;
    const double mean = s / n;
    out.value[i] = mean;
    out.standard_error[i] = n > 1 ? std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1))
                                  : std::numeric_limits<double>::infinity();  // one path: unknown spread
  }
  return out;
}

}  // namespace fenestra
