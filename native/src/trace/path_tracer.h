#pragma once
// Unidirectional path tracer from sensor points (the integrator; what it samples and where its light
// goes have rooms of their own: light_sampling.h, portal_sampler.h, record_sink.h, scene_hits.h):
// cosine-weighted sampling at the sensor, next-event estimation toward the sky with multiple
// importance sampling (sky sampling + BSDF sampling) and toward the sun disks of a daylight sky
// (next-event estimation only), and Russian roulette.
//
// Two modes share one loop:
//  - recording (one pass for all elements): the opening domain is closed, and every time a path
//    segment or a shadow ray reaches an element the tracer records what would arrive through it if it
//    were open (the path continued outside with that element cut), then carries on as if it were closed;
//    In this mode the elements are also light portals: every vertex sends one extra shadow ray
//    toward a point on an element (at the sensor, path p aims at element p mod No, so each
//    element gets the same number of samples), combined with the other two strategies by MIS;
//  - closed: plain radiance estimates with the given cutters really cut (ground truth `evaluate`).
//    The openings are portals of the sky (opening_portals.h): the sensor and every vertex also
//    sample the sky through them, weighed by MIS against BSDF and sky sampling.
#include <memory>

#include "daylight/sky_patches.h"
#include "scene/scene.h"
#include "trace/light_sampling.h"
#include "trace/opening_portals.h"
#include "trace/path_record.h"
#include "trace/path_samples.h"
#include "trace/portal_sampler.h"
#include "trace/record_sink.h"
#include "trace/scene_hits.h"
#include "trace/sensor_range.h"
#include "util/rng.h"

namespace fenestra {

class PathTracer {
 public:
  static constexpr size_t kSensorPortals = PortalSampler::kSensorPortals;
  static constexpr size_t kStratifiedSensorPortals = PortalSampler::kStratifiedSensorPortals;
  size_t stratified_sensor_portals() const { return portals_.stratified_sensor_portals(); }

  // `openings` are cut (closed mode); `reveals` line them through the wall (materials per face).
  // With `patches` (an annual pass: the scene's sky is unit and its suns are the sun clusters), every
  // recorded event names its source: the patch of the sky it came from, or the sun cluster
  // (AnnualSources; records must be `sourced`).
  // In closed mode the sensor and every vertex also sample the sky through the openings
  // (sky_through_openings.h).
  PathTracer(const Scene& scene, CutterSet openings, Mesh reveals, const SkyPatches* patches = nullptr);

  // `samples`, when given, are the path's stratified first decisions (path_samples.h); every
  // other decision comes from `rng`.
  // Closed mode: one-path estimate of sensor i's value (luminance-weighted irradiance).
  float sensor_sample(size_t sensor, const PathSamples* samples, Rng& rng) const;
  // Closed mode, a tracer built with sky patches: the same path's light split by source, as
  // (source, value) pairs appended to `out` (AnnualSources indices; a source may appear more than
  // once, and the sensor's own sun sample keeps its kDirect flag).
  using SourceLight = fenestra::SourceLight;
  void sensor_sample_by_source(size_t sensor, const PathSamples* samples, Rng& rng,
                               std::vector<SourceLight>* out) const;
  // Recording mode: appends the events of path `path` (0 <= path < paths_per_sensor) to `record`,
  // and adds what the path dropped to `dropped` (record_sink.h).
  void record_sensor_path(size_t sensor, size_t path, const PathSamples* samples, Rng& rng,
                          SensorRecord* record, DropCounts* dropped) const;

  // Recording with stratified samples aims each sensor's portal samples by its view of the
  // elements (portal_selection.h): builds that table, once, before record_sensor_path, for the
  // sensors of `range` (only they may then be recorded).
  void prepare_portal_selection(int threads, SensorRange range = {});
  size_t portal_selection_bytes() const { return portals_.selection_bytes(); }

  // Throws std::invalid_argument naming the first sensor of `range` that sits inside a closed solid.
  void check_sensors(SensorRange range = {}) const;

  // The sun seen straight from a sensor along `direction` (a point source): its cosine at the
  // sensor, and, when nothing opaque is in the way with the domain closed except for elements,
  // the elements the ray crosses (all must be open for it to arrive) and the glass's attenuation.
  using Crossing = fenestra::Crossing;
  struct DirectSun {
    bool visible = false;
    float cosine = 0.0f, attenuation = 1.0f;
    std::vector<Crossing> crossed;
  };
  DirectSun direct_sun(size_t sensor, const Vec3& direction) const;
  // Closed mode: the sun seen straight from a sensor with the openings really cut, so it arrives
  // only through their holes (no elements are crossed: `crossed` stays empty).
  DirectSun direct_sun_through_openings(size_t sensor, const Vec3& direction) const;

 private:
  struct PathState;

  // A shadow ray from the sensor along `direction` with `cutters` cut, listing the elements it
  // crosses when `collect`.
  DirectSun sun_from_sensor(size_t sensor, const Vec3& direction, const CutterSet* cutters, bool collect) const;
  void trace_sensor(size_t sensor, size_t path, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                    RecordSink& sink) const;
  // Portal sample toward `aim` from vertex x (normal n, path state st): followed outside with the
  // element there cut; recorded as light that needs that element open.
  // f_and_pdf(dir, &pdf) gives the vertex's BSDF times cosine and BSDF density toward dir.
  template <typename BsdfOfDirection>
  void sample_portal(const PortalSampler::Aim& aim, const Vec3& x, const Vec3& n, const PathState& st, Rng& rng,
                     BsdfOfDirection f_and_pdf, RecordSink& sink) const;
  void trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, RecordSink& sink) const;
  // MIS weight of light found along the current direction (sky_pdf 0 for an outdoor surface).
  static float strategy_weight(const PathState& st, float sky_pdf);
  // A sub-path beyond an element meets element j (its face, or its tube's side from an open
  // neighbour inside a thick wall) at `at`: branches for j open; returns false when the sub-path
  // must stop (too many conditions).
  bool meet_element_outside(const Crossing& j, bool through_face, const Vec3& org, const Vec3& dir, const Vec3& at,
                            PathState& st, const CutterSet* cutters, Rng& rng, RecordSink& sink) const;
  // Records what arrives through k, met at distance t along (org, dir) on its inner face
  // (portals aim there) or its wall's outer face.
  void record_escape(const Crossing& met, bool inner_face, const Vec3& org, const Vec3& dir, float t,
                     const PathState& st, Rng& rng, RecordSink& sink) const;
  // One portal sample from a vertex inside (PortalSampler::sample).
  void sample_interior_portal(const Vertex& v, const PathState& st, const PathSamples* samples, Rng& rng,
                              RecordSink& sink) const;

  const Scene& scene_;
  CutterSet openings_;
  OpeningPortals opening_portals_;  // openings_ as portals of the sky (closed mode)
  SceneHits hits_;
  PortalSampler portals_;
  LightSampling lights_;
};

}  // namespace fenestra
