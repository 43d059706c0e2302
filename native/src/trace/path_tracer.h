#pragma once
// Unidirectional path tracer from sensor points: cosine-weighted sampling at the sensor, next-event
// estimation toward the sky with multiple importance sampling (sky sampling + BSDF sampling) and
// Russian roulette.
//
// Two modes share one loop:
//  - recording (one pass for all elements): the opening domain is closed, and every time a path
//    segment or a shadow ray reaches an element the tracer records what would arrive through it if it
//    were open (the path continued outside with that element cut), then carries on as if it were closed;
//  - closed: plain radiance estimates with the given cutters really cut (ground truth `evaluate`).
#include <memory>

#include "scene/scene.h"
#include "trace/path_record.h"
#include "trace/ray_scene.h"
#include "util/rng.h"

namespace fenestra {

class PathTracer {
 public:
  // `openings` are cut (closed mode); `reveals` line them through the wall (materials per face).
  PathTracer(const Scene& scene, CutterSet openings, Mesh reveals);

  // Closed mode: one-path estimate of sensor i's value (luminance-weighted irradiance).
  float sensor_sample(size_t sensor, Rng& rng) const;
  // Recording mode: appends one path's events to `record` (and ends the path).
  void record_sensor_path(size_t sensor, Rng& rng, SensorRecord* record) const;

  // Throws std::invalid_argument naming the first sensor that sits inside a closed solid.
  void check_sensors() const;

 private:
  struct PathState;
  struct Surface;
  struct Shadow;
  class Sink;

  void trace_sensor(size_t sensor, Rng& rng, const CutterSet* cutters, Sink& sink) const;
  void trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, Sink& sink) const;
  Surface surface(const Hit& hit) const;
  void shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const;

  const Scene& scene_;
  CutterSet openings_;
  Mesh reveals_;
  std::vector<Vec3> scene_normals_, reveal_normals_;
  std::unique_ptr<RayScene> rays_;
};

}  // namespace fenestra
