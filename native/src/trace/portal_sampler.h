#pragma once
// Portal sampling: the elements of the opening domain as lights' portals. In recording mode every
// vertex of a path sends one extra shadow ray toward a point on an element, and the sensor sends
// several; this type draws those points and gives their densities. Like pbrt-v4's light
// samplers, what draws a sample and what gives its density sit side by side: sample() and pdf()
// (an interior vertex's strategy, which the tracer weighs against BSDF and sky sampling by MIS),
// tied by cpp_tests/portal_sampler_test.cpp; the sensor's samples (sensor_portals,
// sensor_stratified) carry their density with them, and nothing is weighed against them.
#include <cstddef>
#include <vector>

#include "math/vec.h"
#include "scene/scene.h"
#include "trace/portal_selection.h"
#include "trace/sensor_range.h"

namespace fenestra {

class PortalSampler {
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

  // The portals are the domain's elements. `render`: the sampler ("sobol" aims interior samples by
  // panel, in solid angle), the seed and the paths per sensor the sensor's samples are spread over.
  PortalSampler(const OpeningDomain& domain, const RenderSettings& render);

  bool empty() const { return portals_.empty(); }
  size_t stratified_sensor_portals() const { return stratified_sensor_portals_; }

  // A point of the domain, its unit normal and its surface area per square meter of panel coordinates.
  struct Point {
    Vec3 position, normal;
    PanelPoint at;
    float area_ratio = 1.0f;
  };
  // Where a portal sample aims, and its density. `solid_angle_pdf` is the direction's density per
  // path when the point was drawn by solid angle; else (0) the point is uniform on portal `portal`
  // by area, drawn `selection` times per path on average (sample_pdf converts).
  struct Aim {
    int portal = -1;  // -1: the element is the one under the point
    int panel = 0;
    Point point;
    float selection = 0.0f;
    float solid_angle_pdf = 0.0f;
  };

  // An interior vertex's portal sample from x (normal n), from u_pick and uv uniform in [0, 1):
  // with render.sampler "sobol", a panel by its share of the elements, then uniform in the solid
  // angle of the rectangle its elements span; else an element at random, then a point by area.
  Aim sample(float u_pick, const Vec2& uv, const Vec3& x, const Vec3& n) const;
  // The solid-angle density with which sample() from `from` yields `dir`, which meets element k
  // first (its inner face), at `distance`, at panel point `at`.
  float pdf(int k, const PanelPoint& at, const Vec3& from, float distance, const Vec3& dir) const;
  // The density of a drawn aim's direction, the point being at `distance` and seen under `cos_at`
  // (the cosine between the direction and the point's normal).
  float sample_pdf(const Aim& aim, float distance, float cos_at) const;

  // The sensor's portal samples of path `path` (independent sampler): kSensorPortals elements
  // swept in turn (from render.seed), a point on each, and that element's selection per path.
  struct SensorPortal {
    int element;
    Vec2 uv;
    float samples_per_path;
  };
  void sensor_portals(size_t sensor, size_t path, SensorPortal* out) const;
  // The sensor's stratified sample j of `count` (render.sampler "sobol", (u, v) from PathSamples):
  // an element by the sensor's view of them (prepare_selection), then uniform in its solid angle,
  // bilinearly after the sensor's cosine.
  Aim sensor_stratified(size_t sensor, size_t count, uint32_t u, float v, const Vec3& x, const Vec3& n) const;
  // Point uv of element k drawn `selection` times per path; `by_solid_angle`: uniform in the solid
  // angle the flat element subtends at x, bilinearly after the cosine about n, else by area.
  Aim aim_at_element(int k, const Vec2& uv, float selection, bool by_solid_angle, const Vec3& x, const Vec3& n) const;

  // Builds, once, the sensors' view-weighted choice of elements (portal_selection.h) for the
  // sensors of `range` (points lifted off their surface as the paths leave them).
  void prepare_selection(const Sensors& sensors, int threads, SensorRange range);
  bool selection_ready(size_t sensors) const { return selection_.size() == sensors; }
  size_t selection_bytes() const;

 private:
  struct Portal {
    Vec3 corner, u, v, normal;  // element square: corner + s u + t v, s, t in [0, 1) (flat panels)
    int panel = 0;
    bool curved = false;         // a patch of a curved panel: the chart cell at `cell`
    PanelPoint cell;             // the element's grid corner in panel coordinates
    Vec2 size;                   // its width and height, meters
  };
  // The panels holding portals, for aim_from_vertex: the rectangle (panel coordinates' bounding box
  // of its portals) as corner + s u + t v, its portals, its share of them and the running total.
  struct PortalPanel {
    int panel = 0;
    bool flat = true;
    Vec3 corner, u, v;
    std::vector<int> portals;
    float share = 0.0f, share_end = 0.0f;
  };

  // The point of portal k at uv (in [0, 1)^2 over its square).
  Point portal_point(int k, const Vec2& uv) const;
  void build_panels();
  Aim aim_from_vertex(float u_pick, const Vec2& uv, const Vec3& x) const;

  const OpeningDomain& domain_;
  uint64_t seed_;
  size_t paths_per_sensor_;
  std::vector<Portal> portals_;
  std::vector<PortalPanel> panels_;
  bool by_panel_ = false;  // interior samples by aim_from_vertex (render.sampler "sobol")
  size_t stratified_sensor_portals_ = kStratifiedSensorPortals;
  std::vector<PortalSelection> selection_;  // per sensor (prepare_selection)
  SensorRange prepared_{0, 0};              // the sensors whose selection is built
};

}  // namespace fenestra
