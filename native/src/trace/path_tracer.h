#pragma once
// Unidirectional path tracer from sensor points: cosine-weighted sampling at the sensor, next-event
// estimation toward the sky with multiple importance sampling (sky sampling + BSDF sampling) and
// toward the sun disks of a daylight sky (next-event estimation only), and Russian roulette.
//
// Two modes share one loop:
//  - recording (one pass for all elements): the opening domain is closed, and every time a path
//    segment or a shadow ray reaches an element the tracer records what would arrive through it if it
//    were open (the path continued outside with that element cut), then carries on as if it were closed;
//    In this mode the elements are also light portals: every vertex sends one extra shadow ray
//    toward a point on an element (at the sensor, path p aims at element p mod No, so each
//    element gets the same number of samples), combined with the other two strategies by MIS;
//  - closed: plain radiance estimates with the given cutters really cut (ground truth `evaluate`).
#include <memory>

#include "daylight/sky_patches.h"
#include "scene/scene.h"
#include "trace/path_record.h"
#include "trace/path_samples.h"
#include "trace/portal_selection.h"
#include "trace/ray_scene.h"
#include "trace/sensor_range.h"
#include "util/rng.h"

namespace fenestra {

class PathTracer {
 public:
  // Portal samples each sensor path sends toward the elements (the direct light through them):
  // 4 balances the direct term (stratified, cheap to improve) against the indirect paths.
  static constexpr size_t kSensorPortals = 4;
  // With stratified samples (render.sampler "sobol"), aimed by the sensor's view and uniform in
  // each element's solid angle, two do better than four did on flat, thin walls (every one lands
  // on an element the sensor sees), at less time and memory per path. On curved panels (sampled
  // by area) and in thick walls (whose tubes the solid angle of the inner face does not see) they
  // keep four.
  static constexpr size_t kStratifiedSensorPortals = 2;
  size_t stratified_sensor_portals() const { return stratified_sensor_portals_; }

  // `openings` are cut (closed mode); `reveals` line them through the wall (materials per face).
  // With `patches` (an annual pass: the scene's sky is unit and its suns are the sun clusters), every
  // recorded event names its source: the patch of the sky it came from, or the sun cluster
  // (AnnualSources; records must be `sourced`).
  PathTracer(const Scene& scene, CutterSet openings, Mesh reveals, const SkyPatches* patches = nullptr);

  // `samples`, when given, are the path's stratified first decisions (path_samples.h); every
  // other decision comes from `rng`.
  // Closed mode: one-path estimate of sensor i's value (luminance-weighted irradiance).
  float sensor_sample(size_t sensor, const PathSamples* samples, Rng& rng) const;
  // Closed mode, a tracer built with sky patches: the same path's light split by source, as
  // (source, value) pairs appended to `out` (AnnualSources indices; a source may appear more than
  // once, and the sensor's own sun sample keeps its kDirect flag).
  struct SourceLight {
    uint16_t source;
    double value;
  };
  void sensor_sample_by_source(size_t sensor, const PathSamples* samples, Rng& rng,
                               std::vector<SourceLight>* out) const;
  // Recording mode: appends the events of path `path` (0 <= path < paths_per_sensor) to `record`.
  void record_sensor_path(size_t sensor, size_t path, const PathSamples* samples, Rng& rng,
                          SensorRecord* record) const;

  // Recording with stratified samples aims each sensor's portal samples by its view of the
  // elements (portal_selection.h): builds that table, once, before record_sensor_path, for the
  // sensors of `range` (only they may then be recorded).
  void prepare_portal_selection(int threads, SensorRange range = {});
  size_t portal_selection_bytes() const;

  // Throws std::invalid_argument naming the first sensor of `range` that sits inside a closed solid.
  void check_sensors(SensorRange range = {}) const;

  // The sun seen straight from a sensor along `direction` (a point source): its cosine at the
  // sensor, and, when nothing opaque is in the way with the domain closed except for elements,
  // the elements the ray crosses (all must be open for it to arrive) and the glass's attenuation.
  // An element met by a ray, and where on its panel.
  struct Crossing {
    int32_t element = -1;
    PanelPoint point;
  };
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
  struct Surface;
  struct Shadow;
  struct Vertex;
  class Sink;

  // What portal sampling aims at: the elements of the unrefined grid (OpeningDomain::portals()).
  struct Portal {
    Vec3 corner, u, v, normal;  // element square: corner + s u + t v, s, t in [0, 1) (flat panels)
    int panel = 0;
    bool curved = false;         // a patch of a curved panel: the chart cell at `cell`
    PanelPoint cell;             // the element's grid corner in panel coordinates
    Vec2 size;                   // its width and height, meters
  };
  // The point of portal k at uv (in [0, 1)^2 over its square), its panel point, its unit normal
  // and its surface area per square meter of panel coordinates.
  struct PortalPoint {
    Vec3 position, normal;
    PanelPoint at;
    float area_ratio = 1.0f;
  };
  PortalPoint portal_point(int k, const Vec2& uv) const;
  void build_portal_panels();

  void trace_sensor(size_t sensor, size_t path, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                    Sink& sink) const;
  // Solid-angle density with which portal sampling at vertex `from` yields `dir`, which meets
  // element k first (in its portal), at `distance`, at panel point `at`.
  float portal_pdf(int k, const PanelPoint& at, const Vec3& from, float distance, const Vec3& dir) const;
  // Where a portal sample aims: a point of the domain, and its density. `solid_angle_pdf` is the
  // direction's density per path when the point was drawn by solid angle; else (0) the point is
  // uniform on portal `portal` by area, drawn `selection` times per path on average.
  struct PortalAim {
    int portal = -1;  // -1: the element is the one under the point
    int panel = 0;
    PortalPoint point;
    float selection = 0.0f;
    float solid_angle_pdf = 0.0f;
  };
  // Point uv of portal k; `by_solid_angle`: uniform in the solid angle the flat element subtends at
  // x, bilinearly after the cosine about n (the sensor's portal samples, which no other strategy is
  // weighed against), else by area.
  PortalAim aim_at_element(int k, const Vec2& uv, float selection, bool by_solid_angle, const Vec3& x,
                           const Vec3& n) const;
  // An interior vertex's portal sample (render.sampler "sobol"): a panel by its share of the
  // elements, then uniform in the solid angle of the rectangle its elements span (portal_pdf agrees).
  PortalAim aim_from_vertex(float u_pick, const Vec2& uv, const Vec3& x) const;
  // Portal sample toward `aim` from vertex x (normal n, path state st): followed outside with the
  // element there cut; recorded as light that needs that element open.
  // f_and_pdf(dir, &pdf) gives the vertex's BSDF times cosine and BSDF density toward dir.
  template <typename BsdfOfDirection>
  void sample_portal(const PortalAim& aim, const Vec3& x, const Vec3& n, const PathState& st, Rng& rng,
                     BsdfOfDirection f_and_pdf, Sink& sink) const;
  // The portal samples a sensor's path sends: element, point on it, and that element's selection.
  struct SensorPortal {
    int element;
    Vec2 uv;
    float samples_per_path;
  };
  void sensor_portals(size_t sensor, size_t path, SensorPortal* out) const;
  void trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, Sink& sink) const;
  // MIS weight of light found along the current direction (sky_pdf 0 for an outdoor surface).
  static float strategy_weight(const PathState& st, float sky_pdf);
  // A sub-path beyond an element meets element j (its face, or its tube's side from an open
  // neighbour inside a thick wall) at `at`: branches for j open; returns false when the sub-path
  // must stop (too many conditions).
  bool meet_element_outside(const Crossing& j, bool through_face, const Vec3& org, const Vec3& dir, const Vec3& at,
                            PathState& st, const CutterSet* cutters, Rng& rng, Sink& sink) const;
  // Records what arrives through element k, met at distance t along (org, dir) on its inner face
  // (portals aim there) or its wall's outer face.
  void record_escape(const Crossing& met, bool inner_face, const Vec3& org, const Vec3& dir, float t, const PathState& st, Rng& rng,
                     Sink& sink) const;
  // The element a ray along dir meets at surface s (point p), or -1 (no element: the panel's margin).
  Crossing crossing_met(const Surface& s, const Vec3& p, const Vec3& dir) const;
  // Next-event estimation toward the sky from a vertex, with `count` samples.
  // `samples` (the main path's first vertex): the first sample is stratified.
  void sample_sky(const Vertex& v, const PathState& st, const CutterSet* cutters, int count,
                  const PathSamples* samples, Rng& rng, Sink& sink) const;
  void sample_sky_once(const Vertex& v, const PathState& st, const CutterSet* cutters, int count, const Vec2& u,
                       Sink& sink) const;
  // Next-event estimation toward the sun disks (nothing else finds them), `count` samples.
  void sample_sun(const Vertex& v, const PathState& st, const CutterSet* cutters, int count,
                  const PathSamples* samples, Rng& rng, Sink& sink) const;
  // One portal sample from a vertex inside: a random element, a random point on it.
  void sample_interior_portal(const Vertex& v, const PathState& st, const PathSamples* samples, Rng& rng,
                              Sink& sink) const;
  Surface surface(const Hit& hit) const;
  // Source of light from the sky along dir, and of sun `index` (0 outside an annual pass).
  uint16_t sky_source(const Vec3& dir) const;
  uint16_t sun_source(int index) const;
  void shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const;

  const Scene& scene_;
  CutterSet openings_;
  Mesh reveals_;
  std::vector<Vec3> scene_normals_, reveal_normals_;
  std::vector<RevealGridFace> reveal_grid_faces_;
  std::unique_ptr<RayScene> rays_;
  std::vector<Portal> portals_;
  std::vector<PortalSelection> portal_selection_;  // per sensor (prepare_portal_selection)
  SensorRange prepared_{0, 0};                     // the sensors whose selection is built
  // The panels holding portals, for aim_from_vertex: the rectangle (panel coordinates' bounding box
  // of its portals) as corner + s u + t v, its portals, its share of them and the running total.
  struct PortalPanel {
    int panel = 0;
    bool flat = true;
    Vec3 corner, u, v;
    std::vector<int> portals;
    float share = 0.0f, share_end = 0.0f;
  };
  std::vector<PortalPanel> portal_panels_;
  bool panel_portals_ = false;  // interior portal samples by aim_from_vertex (render.sampler "sobol")
  size_t stratified_sensor_portals_ = kStratifiedSensorPortals;
  const SkyPatches* patches_ = nullptr;
};

}  // namespace fenestra
