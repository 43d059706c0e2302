#include "trace/path_tracer.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "daylight/annual_sources.h"
#include "sampling/spherical_rectangle.h"
#include "sampling/warp.h"
#include "scene/bsdf.h"
#include "trace/parallel.h"
#include "trace/replicates.h"

namespace fenestra {
namespace {

constexpr float kRayEpsilon = 1e-4f;  // meters: offset of new rays from the surface they leave
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kRouletteDepth = 3;
// Steradians: below, an element is sampled by area (its solid angle's formula loses precision,
// and area sampling is as good there).
constexpr double kMinSolidAngle = 1e-4;
constexpr float kCosineFloor = 0.01f;
constexpr int kMaxCrossed = 32;
constexpr int kOutdoorSkySamples = 4;

// Power heuristic for the strategy with density `pdf` against two others.
float power_heuristic(float pdf, float other, float third = 0.0f) {
  const float a = pdf * pdf, sum = a + other * other + third * third;
  return sum > 0.0f ? a / sum : 0.0f;
}

// Two uniforms in a fixed order (the order of function arguments is unspecified).
Vec2 next2(Rng& rng) {
  const float a = rng.uniform();
  return Vec2(a, rng.uniform());
}

Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  return p + (dir.dot(ng) > 0.0f ? kRayEpsilon : -kRayEpsilon) * ng;
}

std::vector<Vec3> unit_normals(const Mesh& mesh) {
  std::vector<Vec3> n(mesh.triangle_count());
  for (size_t t = 0; t < n.size(); ++t) n[t] = mesh.area_normal(t).normalized();
  return n;
}

}  // namespace

struct PathTracer::PathState {
  Rgb beta;                   // throughput so far (includes the sensor's pi for cosine sampling)
  float prev_pdf = 0.0f;      // BSDF pdf of the direction being followed, for MIS at sky hits
  bool prev_specular = false;
  bool portals = false;        // the vertex that chose this direction also sampled portals
  bool from_sensor = false;    // ... and that vertex was the sensor
  Vec3 vertex;                 // that vertex
  Vec3 vertex_normal = Vec3(0, 0, 1);  // its shading normal (sky densities depend on it)
  float portal_pdf = 0.0f;     // portal density of this direction, once known (at an escape)
  int sky_samples = 1;         // sky samples the vertex that chose this direction took
  bool beyond_element = false;  // followed through an element: the next vertex is the first outside
  // Depth at which a segment through a thick wall follows both ways at each tube side it meets (open
  // neighbour: on; closed: its reveal); deeper, one way at random (meet_element_outside).
  int branch_both_depth = -1;
  float must_reach = 0.0f;      // the first segment counts only if nothing is met before this distance
  bool by_portal = false;      // this direction was chosen by portal sampling (else by the BSDF)
  // At the sensor, portal samples alone carry the light that comes through elements: they are
  // stratified over each element, far better than MIS weights computed from densities assume.
  bool portal_exclusive = false;
  int depth = 0;              // surface interactions so far
  // The main path's first vertex draws its sky, sun and bounce decisions from these (then null;
  // branches and sub-paths never see them).
  const PathSamples* samples = nullptr;
};

struct PathTracer::Surface {
  Vec3 normal;  // unit geometric normal as modelled
  int material = 0;
  int panel = -1;      // opening-domain panel whose inner (domain) or outer face this is
  bool outer = false;  // the outer face of the panel's wall
  int reveal_grid_face = -1;  // a side of an element's tube through a thick wall (RevealGridFace)
  uint32_t triangle = 0;      // the scene triangle, on the scene's geometry
  bool inner_face() const { return panel >= 0 && !outer; }
};

struct PathTracer::Shadow {
  bool visible = false;
  Rgb attenuation = Rgb::Ones();
  std::array<Crossing, kMaxCrossed> crossed;
  std::array<float, kMaxCrossed> crossed_distance;
  int crossed_count = 0;
  bool first_is_element = false;  // the ray met an element before anything else (portals reach it)
};

// A surface interaction: position, normals, shading frame, outgoing direction, material.
struct PathTracer::Vertex {
  Vec3 p;
  Vec3 ng;     // geometric normal as modelled
  Vec3 n;      // shading normal, on the side of wo
  Frame frame;  // around n
  Vec3 wo;     // toward where the path came from, in `frame`
  const Material* material = nullptr;
};

// Where a path's light goes: summed (ground truth), listed by source (ground truth of an annual
// study), recorded as events (a sensor's path), or,
// for a sub-path beyond an element, summed by condition: light found after the sub-path went
// through other elements holds only if they are open, after reflecting off them only if closed.
class PathTracer::Sink {
 public:
  // Conditions of one part: an oblique segment through a thick wall crosses several elements' tubes.
  static constexpr int kMaxConditions = 32;
  // Element faces (inner or outer) a sub-path may go on through, beyond its own; crossings from one
  // element's tube into its neighbour's inside the wall are limited by kMaxConditions only.
  static constexpr int kMaxPassed = 3;

  static Sink sum() { return Sink(nullptr, false); }
  // `cells`: the domain's elements, where the record keeps its points (CellPoint).
  static Sink record(SensorRecord* record, const std::vector<Element>* cells) {
    Sink sink(record, false);
    sink.cells_ = cells;
    return sink;
  }
  static Sink outside() { return Sink(nullptr, true); }
  // Closed mode, light listed by source as it arrives (an annual study with the openings cut).
  static Sink by_source(std::vector<SourceLight>* out) {
    Sink sink(nullptr, false);
    sink.by_source_ = out;
    return sink;
  }

  bool recording() const { return record_ != nullptr; }
  bool outside_element() const { return outside_; }

  // `source`: the light's source in an annual pass (AnnualSources), else 0.
  void light(const Rgb& c, const Crossing* crossed, int count, uint16_t source) {
    light(luminance(c), crossed, count, source);
  }
  void light(float v, const Crossing* crossed, int count, uint16_t source) {
    if (!(v > 0.0f) || !std::isfinite(v)) return;
    Part& current = parts_[current_];
    if (record_) {
      push(v, -1, {}, 0, crossed, count, nullptr, 0, source);
    } else if (by_source_ && count == 0) {
      by_source_->push_back({source, v});
    } else if (count == 0 && (current.source == source || current.value == 0.0)) {
      current.value += v;
      current.source = source;
    } else if (condition_count() + count <= kMaxConditions) {
      // Outside, a shadow ray through other elements: light that needs them open as well (or, in
      // an annual pass, light of another source under the same conditions).
      Part part = current;
      part.value = v;
      part.source = source;
      auto closed = part.conditions.begin() + part.open_count;
      std::copy_backward(closed, closed + part.closed_count, closed + part.closed_count + count);
      std::copy(crossed, crossed + count, closed);
      part.open_count += static_cast<uint8_t>(count);
      parts_.push_back(part);
    }
  }
  // Outside: a sub-path that went on through element j (its light needs j open), if the
  // conditions leave room; the caller traces into it and absorb()s it.
  bool can_pass(bool through_face) const {
    return condition_count() < kMaxConditions && (!through_face || parts_[current_].passes < kMaxPassed);
  }
  Sink passing(const Crossing& j, bool through_face) const {
    Sink child = Sink::outside();
    Part& part = child.parts_[0];
    part = parts_[current_];
    part.value = 0.0;
    if (through_face) ++part.passes;
    auto closed = part.conditions.begin() + part.open_count;  // open conditions stay first
    std::copy_backward(closed, closed + part.closed_count, closed + part.closed_count + 1);
    part.conditions[part.open_count++] = j;
    return child;
  }
  void absorb(const Sink& child) {
    for (const Part& part : child.parts_)
      if (part.value != 0.0) parts_.push_back(part);
  }
  // Outside: from now on, the light found needs element j closed. Returns false when the
  // conditions are full (the caller stops: what follows is not recorded).
  bool reflect_off(const Crossing& j) {
    if (condition_count() >= kMaxConditions) return false;
    Part next = parts_[current_];
    next.value = 0.0;
    next.conditions[next.open_count + next.closed_count++] = j;
    parts_.push_back(next);
    current_ = parts_.size() - 1;
    return true;
  }
  // Recording: what `outside` found beyond element k, reached by the path (an escape) ...
  void escape(const Crossing& k, const Sink& outside) {
    push(finite(outside.parts_[0].value), k.element, k.point, 0, nullptr, 0, nullptr, 0, outside.parts_[0].source);
    for (size_t n = 1; n < outside.parts_.size(); ++n) {
      const Part& part = outside.parts_[n];
      if (part.value == 0.0) continue;
      push(finite(part.value), k.element, k.point, PathEvent::kEscapePart, part.conditions.data(), part.open_count,
           part.conditions.data() + part.open_count, part.closed_count, part.source);
    }
  }
  // ... or reached by a portal sample (light that needs k open).
  void light_through(const Crossing& k, const Sink& outside) {
    for (const Part& part : outside.parts_) {
      if (!(part.value > 0.0) || !std::isfinite(part.value)) continue;
      std::array<Crossing, kMaxConditions + 1> open;
      open[0] = k;
      std::copy(part.conditions.begin(), part.conditions.begin() + part.open_count, open.begin() + 1);
      push(static_cast<float>(part.value), -1, {}, 0, open.data(), part.open_count + 1,
           part.conditions.data() + part.open_count, part.closed_count, part.source);
    }
  }
  double total() const {
    double t = 0.0;
    for (const Part& part : parts_) t += part.value;
    return t;
  }

 private:
  struct Part {
    double value = 0.0;
    uint8_t open_count = 0, closed_count = 0;
    uint8_t passes = 0;  // element faces gone through
    uint16_t source = 0;  // of the light it holds (annual pass)
    std::array<Crossing, kMaxConditions> conditions{};  // open ones first
  };

  Sink(SensorRecord* record, bool outside) : record_(record), outside_(outside), parts_(1) {}
  int condition_count() const { return parts_[current_].open_count + parts_[current_].closed_count; }
  static float finite(double v) { return std::isfinite(v) ? static_cast<float>(v) : 0.0f; }
  void push(float v, int element, const PanelPoint& at, uint8_t flags, const Crossing* open, size_t open_count,
            const Crossing* closed, size_t closed_count, uint16_t source) {
    static_assert(kMaxCrossed <= kMaxConditions + 1, "a shadow ray's crossings must fit an event's conditions");
    std::array<MetElement, kMaxConditions + 1> met;
    for (size_t i = 0; i < open_count; ++i) met[i] = this->met(open[i]);
    for (size_t i = 0; i < closed_count; ++i) met[open_count + i] = this->met(closed[i]);
    if (element < 0)
      record_->add_light(v, met.data(), open_count, met.data() + open_count, closed_count);
    else
      record_->add_escape(v, this->met({element, at}), flags & PathEvent::kEscapePart, met.data(), open_count,
                          met.data() + open_count, closed_count);
    if (record_->sourced) record_->event_sources.push_back(source);
  }
  MetElement met(const Crossing& c) const { return {c.element, CellPoint::of((*cells_)[c.element], c.point)}; }

  SensorRecord* record_;
  const std::vector<Element>* cells_ = nullptr;
  bool outside_;
  std::vector<SourceLight>* by_source_ = nullptr;
  std::vector<Part> parts_;  // parts_[current_] takes the light now
  size_t current_ = 0;
};

PathTracer::PathTracer(const Scene& scene, CutterSet openings, Mesh reveals, const SkyPatches* patches)
    : scene_(scene), openings_(std::move(openings)), reveals_(std::move(reveals)), patches_(patches) {
  scene_normals_ = unit_normals(scene_.mesh);
  reveal_normals_ = unit_normals(reveals_);
  const Mesh reveal_grid = scene_.domain.reveal_grid(&reveal_grid_faces_);
  rays_ = std::make_unique<RayScene>(scene_.mesh, reveals_, reveal_grid);
  for (const Element& e : scene_.domain.portals()) {
    const Panel& panel = scene_.domain.panels()[e.panel];
    portals_.push_back({e.corners[0], e.width() * panel.u_axis, e.height() * panel.v_axis, panel.normal, e.panel,
                        panel.curved(), {e.u0, e.v0}, {e.width(), e.height()}});
  }
  build_portal_panels();
}

void PathTracer::build_portal_panels() {
  panel_portals_ = scene_.render.sampler == RenderSettings::Sampler::kSobol && !portals_.empty();
  std::vector<int> index_of_panel(scene_.domain.panels().size(), -1);
  for (size_t k = 0; k < portals_.size(); ++k) {
    const int panel = portals_[k].panel;
    if (index_of_panel[panel] < 0) {
      index_of_panel[panel] = static_cast<int>(portal_panels_.size());
      portal_panels_.push_back({});
      portal_panels_.back().panel = panel;
      portal_panels_.back().flat = !scene_.domain.panels()[panel].curved();
    }
    portal_panels_[index_of_panel[panel]].portals.push_back(static_cast<int>(k));
  }
  float running = 0.0f;
  for (PortalPanel& p : portal_panels_) {
    const Panel& panel = scene_.domain.panels()[p.panel];
    float u0 = kInfinity, v0 = kInfinity, u1 = -kInfinity, v1 = -kInfinity;
    for (const int k : p.portals) {
      const Portal& portal = portals_[k];
      u0 = std::min(u0, portal.cell.u), v0 = std::min(v0, portal.cell.v);
      u1 = std::max(u1, portal.cell.u + portal.size.x()), v1 = std::max(v1, portal.cell.v + portal.size.y());
    }
    p.corner = panel.origin + u0 * panel.u_axis + v0 * panel.v_axis;
    p.u = (u1 - u0) * panel.u_axis;
    p.v = (v1 - v0) * panel.v_axis;
    p.share = static_cast<float>(p.portals.size()) / static_cast<float>(portals_.size());
    running += p.share;
    p.share_end = running;
  }
  if (!portal_panels_.empty()) portal_panels_.back().share_end = 1.0f;
  bool all_flat = true;
  for (const PortalPanel& p : portal_panels_) all_flat = all_flat && p.flat;
  stratified_sensor_portals_ = all_flat && !scene_.domain.has_thick_walls() ? kStratifiedSensorPortals : kSensorPortals;
}

namespace {
float radical_inverse(uint32_t index, uint32_t base) {
  const float inv = 1.0f / static_cast<float>(base);
  float result = 0.0f, digit = inv;
  for (; index > 0; index /= base, digit *= inv) result += static_cast<float>(index % base) * digit;
  return result;
}
}  // namespace

void PathTracer::sensor_portals(size_t sensor, size_t path, SensorPortal* out) const {
  // Within each replicate group (replicates.h) the sensor's portal samples sweep the elements in
  // turn from a random start, so every element gets its share of samples up to one; successive
  // visits to an element take successive Halton points with a random shift (Cranley-Patterson),
  // evenly spread over it, which nearby elements need. Groups are independent randomisations.
  // A sample is weighted by the inverse of its element's expected visits per path: when the group
  // has samples for every element, the visits are known and at least one (a mean of unbiased
  // points); with fewer samples than elements, an element is visited once or not at all, with
  // probability samples / elements over the random start (Horvitz-Thompson), so the light of the
  // unvisited elements is still counted in expectation.
  const size_t no = portals_.size();
  const size_t group = replicate_of(path);
  const size_t group_paths = replicate_size(group, static_cast<size_t>(scene_.render.paths_per_sensor));
  const uint64_t key = mix_seed(mix_seed(scene_.render.seed, sensor), 0x9047A1 + group);
  const size_t start = Rng(key, 0).next_u32() % no;
  const size_t first = start + (path / kReplicates) * kSensorPortals;
  const size_t group_samples = group_paths * kSensorPortals;
  const size_t end = start + group_samples;  // the group's samples: [start, end)
  for (size_t j = 0; j < kSensorPortals; ++j) {
    const size_t t = first + j;
    const size_t k = t % no;
    const size_t first_visit = start + (k + no - start % no) % no;  // first t >= start with t % no == k
    const size_t visits = (end - 1 - first_visit) / no + 1;
    const uint32_t visit = static_cast<uint32_t>((t - first_visit) / no);
    Rng shift(key, 1 + k);
    const float a = radical_inverse(visit, 2) + shift.uniform(), b = radical_inverse(visit, 3) + shift.uniform();
    out[j].element = static_cast<int>(k);
    out[j].uv = Vec2(std::min(a - std::floor(a), 0.99999994f), std::min(b - std::floor(b), 0.99999994f));
    out[j].samples_per_path = group_samples >= no
                                  ? static_cast<float>(visits) / static_cast<float>(group_paths)
                                  : static_cast<float>(static_cast<double>(kSensorPortals) / static_cast<double>(no));
  }
}


PathTracer::PortalPoint PathTracer::portal_point(int k, const Vec2& uv) const {
  const Portal& portal = portals_[k];
  PortalPoint out;
  if (!portal.curved) {
    out.position = portal.corner + uv.x() * portal.u + uv.y() * portal.v;
    out.normal = portal.normal;
    out.at = scene_.domain.panel_point(portal.panel, out.position);
    return out;
  }
  out.at = {portal.cell.u + uv.x() * portal.size.x(), portal.cell.v + uv.y() * portal.size.y()};
  const DomainSurfacePoint s = scene_.domain.surface_at(portal.panel, out.at.u, out.at.v);
  out.position = s.position;
  out.normal = s.outward;
  out.area_ratio = s.area_ratio;
  return out;
}

float PathTracer::portal_pdf(int k, const PanelPoint& at, const Vec3& from, float distance, const Vec3& dir) const {
  const int panel = scene_.domain.elements()[k].panel;
  const PortalPanel* portal_panel = nullptr;
  if (panel_portals_) {
    for (const PortalPanel& p : portal_panels_)
      if (p.panel == panel) portal_panel = &p;
    if (!portal_panel) return 0.0f;
    if (portal_panel->flat) {  // aim_from_vertex: uniform in the solid angle of the panel's rectangle
      const double omega = rectangle_solid_angle(from, portal_panel->corner, portal_panel->u, portal_panel->v);
      if (omega > kMinSolidAngle) return portal_panel->share / static_cast<float>(omega);
    }
  }
  // An element chosen among all (or among its panel's), then a uniform point of its square in panel
  // coordinates, converted to solid angle (on a curved panel, through the surface's area there).
  // On a refined domain, the portal is the unrefined element under the point.
  const int portal_index = scene_.domain.is_refined() ? scene_.domain.portal_at(panel, at) : k;
  if (portal_index < 0) return 0.0f;
  const Portal& portal = portals_[portal_index];
  Vec3 normal = portal.normal;
  float area_ratio = 1.0f;
  if (portal.curved) {
    const DomainSurfacePoint s = scene_.domain.surface_at(portal.panel, at.u, at.v);
    normal = s.outward;
    area_ratio = s.area_ratio;
  }
  const float cos = std::abs(dir.dot(normal));
  if (!(cos > 1e-6f)) return 0.0f;
  const float element_area = portal.size.x() * portal.size.y();
  const float selection = portal_panel ? portal_panel->share / static_cast<float>(portal_panel->portals.size())
                                       : 1.0f / static_cast<float>(portals_.size());
  return selection * distance * distance / (element_area * area_ratio * cos);
}

PathTracer::PortalAim PathTracer::aim_at_element(int k, const Vec2& uv, float selection, bool by_solid_angle,
                                                 const Vec3& x, const Vec3& n) const {
  const Portal& square = portals_[k];
  PortalAim aim;
  aim.portal = k;
  aim.panel = square.panel;
  aim.selection = selection;
  // A flat element seen under a fair solid angle is sampled uniformly in it (sampling by area
  // would leave the estimate the 1/d^2 and cosine of a near element to average out) ...
  const double omega =
      by_solid_angle && !square.curved ? rectangle_solid_angle(x, square.corner, square.u, square.v) : 0.0;
  if (omega > kMinSolidAngle) {
    const SphericalRectangle seen(x, square.corner, square.u, square.v);
    // ... and, within it, bilinearly after the receiver's cosine toward the corners (floored: the
    // density must stay positive wherever the cosine is).
    const Vec3 corners[4] = {square.corner, square.corner + square.u, square.corner + square.v,
                             square.corner + square.u + square.v};
    float w[4];
    for (int c = 0; c < 4; ++c) w[c] = std::max(kCosineFloor, (corners[c] - x).normalized().dot(n));
    const Vec2 warped = square_to_bilinear(uv, w);
    aim.point.position = seen.sample(warped);
    aim.point.normal = square.normal;
    aim.point.at = scene_.domain.panel_point(square.panel, aim.point.position);
    aim.solid_angle_pdf = selection * bilinear_pdf(warped, w) / static_cast<float>(omega);
  } else {
    aim.point = portal_point(k, uv);
  }
  return aim;
}

PathTracer::PortalAim PathTracer::aim_from_vertex(float u_pick, const Vec2& uv, const Vec3& x) const {
  // A panel by its share of the elements, then a point uniform in the solid angle of the
  // rectangle its elements span (flat panels), or an element of it and a point by area.
  size_t p = 0;
  while (p + 1 < portal_panels_.size() && u_pick >= portal_panels_[p].share_end) ++p;
  const PortalPanel& panel = portal_panels_[p];
  const float begin = p == 0 ? 0.0f : portal_panels_[p - 1].share_end;
  const float remainder = std::clamp((u_pick - begin) / (panel.share_end - begin), 0.0f, 0.99999994f);
  PortalAim aim;
  aim.panel = panel.panel;
  const double omega = panel.flat ? rectangle_solid_angle(x, panel.corner, panel.u, panel.v) : 0.0;
  if (omega > kMinSolidAngle) {
    aim.point.position = SphericalRectangle(x, panel.corner, panel.u, panel.v).sample(uv);
    aim.point.normal = scene_.domain.panels()[panel.panel].normal;
    aim.point.at = scene_.domain.panel_point(panel.panel, aim.point.position);
    aim.solid_angle_pdf = panel.share / static_cast<float>(omega);
    return aim;
  }
  const size_t count = panel.portals.size();
  aim.portal = panel.portals[std::min(count - 1, static_cast<size_t>(remainder * count))];
  aim.selection = panel.share / static_cast<float>(count);
  aim.point = portal_point(aim.portal, uv);
  return aim;
}

template <typename BsdfOfDirection>
void PathTracer::sample_portal(const PortalAim& aim, const Vec3& x, const Vec3& n, const PathState& st, Rng& rng,
                               BsdfOfDirection f_and_pdf, Sink& sink) const {
  const PortalPoint& portal = aim.point;
  const Vec3& y = portal.position;
  if (!is_finite(y)) return;
  Vec3 dir = y - x;
  const float dist = dir.norm();
  if (!(dist > 1e-5f)) return;
  dir /= dist;
  if (dir.dot(n) <= 0.0f) return;
  float bsdf_pdf = 0.0f;
  const Rgb f = f_and_pdf(dir, &bsdf_pdf);
  if (!(f > 0.0f).any()) return;
  const float cos_y = std::abs(dir.dot(portal.normal));
  if (!(cos_y > 1e-6f)) return;
  float pdf = aim.solid_angle_pdf;  // of the direction, per path
  if (pdf == 0.0f) {
    const Vec2& size = portals_[aim.portal].size;
    pdf = aim.selection * dist * dist / (size.x() * size.y() * portal.area_ratio * cos_y);
  }
  // Everything that arrives through k along dir: sky, and light from outdoor surfaces.
  PathState through_state = st;
  through_state.beta = st.beta * f / pdf;
  through_state.prev_pdf = bsdf_pdf;
  through_state.prev_specular = false;
  through_state.portals = false;
  through_state.portal_pdf = pdf;
  through_state.by_portal = true;
  through_state.vertex = x;
  through_state.vertex_normal = n;
  through_state.beyond_element = true;
  through_state.must_reach = dist;  // portals only reach what lies beyond the element met first
  through_state.branch_both_depth = st.depth;
  // The element under the point (on a refined grid, one of the portal's cells).
  const int element = aim.portal >= 0 && !scene_.domain.is_refined() ? aim.portal
                                                                      : scene_.domain.element_at(aim.panel, portal.at);
  if (element < 0) return;
  const CutterSet through{scene_.domain.element_cutter(element)};
  Sink outside = Sink::outside();
  trace(x, dir, through_state, &through, rng, outside);
  sink.light_through({element, portal.at}, outside);
}

PathTracer::Surface PathTracer::surface(const Hit& hit) const {
  Surface s;
  if (hit.geometry == RayScene::kRevealGeometry) {
    s.normal = reveal_normals_[hit.primitive];
    s.material = reveals_.triangle_material[hit.primitive];
  } else if (hit.geometry == RayScene::kRevealGridGeometry) {
    s.reveal_grid_face = static_cast<int>(hit.primitive / 2);  // two triangles per face
    const RevealGridFace& f = reveal_grid_faces_[s.reveal_grid_face];
    s.normal = f.normal;
    s.material = scene_.domain.panels()[f.panel].material;
  } else {
    s.normal = scene_normals_[hit.primitive];
    s.material = scene_.mesh.triangle_material[hit.primitive];
    s.triangle = hit.primitive;
    s.panel = scene_.domain.panel_of_triangle(hit.primitive);
    if (s.panel < 0) {
      s.panel = scene_.domain.outer_panel_of_triangle(hit.primitive);
      s.outer = s.panel >= 0;
    }
  }
  return s;
}

PathTracer::Crossing PathTracer::crossing_met(const Surface& s, const Vec3& p, const Vec3& dir) const {
  if (s.reveal_grid_face >= 0) {  // the cell the ray would go on into
    const RevealGridFace& f = reveal_grid_faces_[s.reveal_grid_face];
    const int k = dir.dot(f.normal) > 0.0f ? f.upper : f.lower;
    // The hit lies on the grid line between two cells, where "inside an opening" is a matter of
    // rounding: the cell's centre stands for it (tubes follow the grid).
    if (k < 0) return {};
    return {k, scene_.domain.panel_point(f.panel, scene_.domain.elements()[k].center)};
  }
  if (s.panel < 0) return {};
  const PanelPoint at = scene_.domain.panel_point(s.panel, s.triangle, p);
  return {scene_.domain.element_at(s.panel, at), at};
}

void PathTracer::shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const {
  out->visible = false;
  out->attenuation = Rgb::Ones();
  out->crossed_count = 0;
  out->first_is_element = false;
  // Elements crossed so far are cut too, through the wall thickness (the set is built on the
  // first crossing: most shadow rays cross none).
  CutterSet with_crossed;
  const CutterSet* active = cutters;
  float tnear = 0.0f;
  for (int i = 0; i < 64; ++i) {
    const Hit h = rays_->intersect(org, dir, tnear, kInfinity, active);
    if (!h.valid()) {
      out->visible = true;
      return;
    }
    const Surface s = surface(h);
    tnear = h.t + kRayEpsilon;
    if (collect && (s.panel >= 0 || s.reveal_grid_face >= 0)) {
      const Crossing crossing = crossing_met(s, org + h.t * dir, dir);
      const int k = crossing.element;
      if (k < 0 || out->crossed_count == kMaxCrossed) return;  // the panel's margin is always wall
      if (i == 0 && s.inner_face()) out->first_is_element = true;
      out->crossed_distance[out->crossed_count] = h.t;
      out->crossed[out->crossed_count++] = crossing;
      if (active != &with_crossed) {
        if (cutters) with_crossed = *cutters;
        active = &with_crossed;
      }
      with_crossed.push_back(scene_.domain.element_cutter(k));
      continue;
    }
    const Material& m = scene_.materials[s.material];
    if (!m.is_thin_glass()) return;
    out->attenuation *= thin_glass_transmittance(m, std::abs(dir.dot(s.normal)));
  }
}

float PathTracer::strategy_weight(const PathState& st, float sky_pdf) {
  if (st.prev_specular) return 1.0f;
  if (st.portal_exclusive && st.portal_pdf > 0.0f) return st.by_portal ? 1.0f : 0.0f;
  return st.by_portal ? power_heuristic(st.portal_pdf, st.prev_pdf, sky_pdf)
                      : power_heuristic(st.prev_pdf, sky_pdf, st.portal_pdf);
}

void PathTracer::record_escape(const Crossing& met, bool inner_face, const Vec3& org, const Vec3& dir, float t, const PathState& st,
                               Rng& rng, Sink& sink) const {
  Sink outside = Sink::outside();
  // From the sensor, portal samples alone carry the light arriving through elements' inner faces.
  if (!(st.portals && st.from_sensor && inner_face)) {
    PathState outside_state = st;
    outside_state.beyond_element = true;
    outside_state.branch_both_depth = st.depth;
    if (st.portals && inner_face) {
      const float distance = (org + t * dir - st.vertex).norm();
      outside_state.portal_pdf = portal_pdf(met.element, met.point, st.vertex, distance, dir);
    }
    // What would arrive through k if it were open: the same ray, continued with k cut.
    const CutterSet through{scene_.domain.element_cutter(met.element)};
    trace(org, dir, outside_state, &through, rng, outside);
  }
  sink.escape(met, outside);
}

void PathTracer::sample_sky(const Vertex& v, const PathState& st, const CutterSet* cutters, int count,
                            const PathSamples* samples, Rng& rng, Sink& sink) const {
  for (int i = 0; i < count; ++i) {
    const Vec2 u = samples && i == 0 ? samples->get2d(PathSamples::kVertexSky) : next2(rng);
    sample_sky_once(v, st, cutters, count, u, sink);
  }
}

void PathTracer::sample_sky_once(const Vertex& v, const PathState& st, const CutterSet* cutters, int count,
                                 const Vec2& u, Sink& sink) const {
  const Sky& sky = *scene_.sky;
  float light_pdf = 0.0f;
  const Vec3 wl = sky.sample_toward(u, v.n, &light_pdf);
  if (!(light_pdf > 0.0f) || wl.dot(v.n) <= 0.0f) return;
  const Vec3 wl_local = v.frame.to_local(wl);
  const Rgb f = bsdf_eval(*v.material, v.wo, wl_local);
  if (!(f > 0.0f).any()) return;
  Shadow sh;
  shadow(offset_origin(v.p, v.ng, wl), wl, cutters, sink.recording() || sink.outside_element(), &sh);
  if (!sh.visible) return;
  const float portal = sink.recording() && sh.first_is_element
                           ? portal_pdf(sh.crossed[0].element, sh.crossed[0].point, v.p, sh.crossed_distance[0], wl)
                           : 0.0f;
  const float w = power_heuristic(count * light_pdf, bsdf_pdf(*v.material, v.wo, wl_local), portal);
  sink.light(st.beta * f * sky.radiance(wl) * sh.attenuation * (w / (count * light_pdf)), sh.crossed.data(),
             sh.crossed_count, sky_source(wl));
}

void PathTracer::sample_sun(const Vertex& v, const PathState& st, const CutterSet* cutters, int count,
                            const PathSamples* samples, Rng& rng, Sink& sink) const {
  for (int i = 0; i < count; ++i) {
    const bool stratified = samples && i == 0;
    const float u_pick = stratified ? samples->get1d(PathSamples::kVertexSunPick) : rng.uniform();
    const Vec2 u_disk = stratified ? samples->get2d(PathSamples::kVertexSun) : next2(rng);
    const SunLights::Sample sun = scene_.suns.sample(u_pick, u_disk);
    if (sun.direction.dot(v.n) <= 0.0f) continue;
    const Rgb f = bsdf_eval(*v.material, v.wo, v.frame.to_local(sun.direction));
    if (!(f > 0.0f).any()) continue;
    Shadow sh;
    shadow(offset_origin(v.p, v.ng, sun.direction), sun.direction, cutters,
           sink.recording() || sink.outside_element(), &sh);
    if (!sh.visible) continue;
    sink.light(st.beta * f * sun.illuminance * sh.attenuation / static_cast<float>(count), sh.crossed.data(),
               sh.crossed_count, sun_source(sun.index));
  }
}

void PathTracer::sample_interior_portal(const Vertex& v, const PathState& st, const PathSamples* samples, Rng& rng,
                                        Sink& sink) const {
  const float u_pick = samples ? samples->get1d(PathSamples::kVertexPortalPick) : rng.uniform();
  const Vec2 uv = samples ? samples->get2d(PathSamples::kVertexPortal) : next2(rng);
  PortalAim aim;
  if (panel_portals_) {
    aim = aim_from_vertex(u_pick, uv, v.p);
  } else {
    const int k = std::min(static_cast<int>(u_pick * portals_.size()), static_cast<int>(portals_.size()) - 1);
    aim = aim_at_element(k, uv, 1.0f / static_cast<float>(portals_.size()), false, v.p, v.n);
  }
  PathState from_here = st;
  ++from_here.depth;
  sample_portal(aim, offset_origin(v.p, v.ng, v.n), v.n, from_here, rng,
                [&](const Vec3& d, float* pdf) {
                  const Vec3 local = v.frame.to_local(d);
                  *pdf = bsdf_pdf(*v.material, v.wo, local);
                  return bsdf_eval(*v.material, v.wo, local);
                },
                sink);
}

bool PathTracer::meet_element_outside(const Crossing& j, bool through_face, const Vec3& org, const Vec3& dir,
                                      const Vec3& at, PathState& st,
                                      const CutterSet* cutters, Rng& rng, Sink& sink) const {
  if (!sink.can_pass(through_face)) return sink.reflect_off(j);
  auto pass = [&](const PathState& state) {
    Sink passing = sink.passing(j, through_face);
    CutterSet through = cutters ? *cutters : CutterSet{};
    through.push_back(scene_.domain.element_cutter(j.element));
    trace(org, dir, state, &through, rng, passing);
    sink.absorb(passing);
  };
  // Inside a thick wall, after the first vertex beyond the element, both ways would multiply at every
  // tube side: one is followed, chosen at random and weighted by the inverse of its probability, so
  // that the records stay unbiased for every set of open elements. Along one straight line the
  // sides met end where it reflects (a closed cell) or leaves the wall: with m sides left on it,
  // this one included, reflecting here has probability 1 / (m + 1), which makes each of the m + 1
  // ends equally likely and weighs every one m + 1 (an even choice at each side would weigh the
  // last 2^m: heavy tails on fine grids). On a refined grid (a local search's, cut every few
  // centimetres) the segment entering the wall crosses many sides too: following both ways at
  // each would trace a reveal sub-path per side, so it chooses as well.
  if (!through_face && (st.depth != st.branch_both_depth || scene_.domain.is_refined())) {
    const int panel = scene_.domain.elements()[j.element].panel;
    const int m = 1 + scene_.domain.lines_ahead(panel, at, dir);
    const float reflect = 1.0f / static_cast<float>(m + 1);
    if (rng.uniform() >= reflect) {
      PathState passing = st;
      passing.beta /= 1.0f - reflect;
      pass(passing);
      return false;
    }
    st.beta /= reflect;
    return sink.reflect_off(j);
  }
  // Were j open, the sub-path would go on through it: follow that too.
  pass(st);
  // Closed, it is wall: what follows needs it closed.
  return sink.reflect_off(j);
}

void PathTracer::trace(Vec3 org, Vec3 dir, PathState st, const CutterSet* cutters, Rng& rng, Sink& sink) const {
  const Sky& sky = *scene_.sky;
  for (;;) {
    const PathSamples* samples = st.samples;
    st.samples = nullptr;
    const Hit h = rays_->intersect(org, dir, 0.0f, kInfinity, cutters);
    if (st.must_reach > 0.0f) {
      if (h.valid() && h.t < st.must_reach - kRayEpsilon) return;
      st.must_reach = 0.0f;
    }
    if (!h.valid()) {
      sink.light(st.beta * sky.radiance(dir) * strategy_weight(st, st.sky_samples * sky.pdf_toward(dir, st.vertex_normal)), nullptr, 0,
                 sky_source(dir));
      return;
    }
    const Surface s = surface(h);
    Vertex v;
    v.p = org + h.t * dir;
    if (sink.recording() || sink.outside_element()) {
      // An element's face (inner or outer), or the side of an open element's tube through a thick
      // wall, which is the reveal of a closed neighbour or the way on into an open one.
      const Crossing met = crossing_met(s, v.p, dir);
      if (met.element >= 0 && sink.recording()) record_escape(met, s.inner_face(), org, dir, h.t, st, rng, sink);
      const bool through_face = s.reveal_grid_face < 0;
      if (met.element >= 0 && sink.outside_element() &&
          !meet_element_outside(met, through_face, org, dir, v.p, st, cutters, rng, sink))
        return;
    }
    if (st.portal_pdf > 0.0f) {
      // First surface beyond an element: reached by BSDF and portal sampling alike.
      st.beta *= strategy_weight(st, 0.0f);
      st.portal_pdf = 0.0f;
      st.by_portal = false;
    }
    if (st.depth >= scene_.render.max_bounces) return;

    v.material = &scene_.materials[s.material];
    v.ng = s.normal;
    const bool front = dir.dot(s.normal) < 0.0f;
    v.n = front ? s.normal : Vec3(-s.normal);
    v.frame = Frame(v.n);
    v.wo = v.frame.to_local(-dir);
    // The first vertex outside an element carries the light of the outdoors into the room for
    // many paths: it takes several sky samples.
    // (Not a reveal inside a thick wall: it is met by many branches of one path, and lights little.)
    const int sky_samples = st.beyond_element && s.reveal_grid_face < 0 ? kOutdoorSkySamples : 1;
    st.beyond_element = false;
    if (!v.material->is_glass()) {
      sample_sky(v, st, cutters, sky_samples, samples, rng, sink);
      if (!scene_.suns.empty()) sample_sun(v, st, cutters, sky_samples, samples, rng, sink);
      if (sink.recording() && !portals_.empty()) sample_interior_portal(v, st, samples, rng, sink);
    }

    BsdfSample bs;
    const Vec2 u = samples ? samples->get2d(PathSamples::kVertexBsdf) : next2(rng);
    const float u_lobe = samples ? samples->get1d(PathSamples::kVertexLobe) : rng.uniform();
    if (!bsdf_sample(*v.material, v.wo, u, u_lobe, front, &bs)) return;
    const Vec3 wi = v.frame.to_world(bs.wi);
    st.beta *= bs.weight;
    if (!bs.straight) {  // thin-glass transmission keeps the direction, and with it the MIS state
      st.prev_pdf = bs.pdf;
      st.prev_specular = bs.specular;
      st.portals = sink.recording() && !v.material->is_glass();
      st.from_sensor = false;
      st.vertex = v.p;
      st.vertex_normal = v.n;
      st.portal_pdf = 0.0f;
      st.sky_samples = v.material->is_glass() ? 1 : sky_samples;
    }
    ++st.depth;
    org = offset_origin(v.p, s.normal, wi);
    dir = wi;

    if (st.depth >= kRouletteDepth) {
      const float q = std::min(0.95f, st.beta.maxCoeff());  // relative to the sensor's unit weight
      if (!(rng.uniform() < q)) return;
      st.beta /= q;
    }
  }
}

void PathTracer::trace_sensor(size_t i, size_t path, const PathSamples* samples, Rng& rng, const CutterSet* cutters,
                              Sink& sink) const {
  const Sky& sky = *scene_.sky;
  const Vec3& n = scene_.sensors.normals[i];
  const Vec3 p = scene_.sensors.points[i] + kRayEpsilon * n;
  const Frame frame(n);

  // The sensor is a cosine receiver: its "BSDF times cosine" is cos(theta).
  float light_pdf = 0.0f;
  const Vec3 wl = sky.sample_toward(samples ? samples->get2d(PathSamples::kSensorSky) : next2(rng), n, &light_pdf);
  const float cos_l = wl.dot(n);
  const bool portals = sink.recording() && !portals_.empty();
  if (light_pdf > 0.0f && cos_l > 0.0f) {
    Shadow sh;
    shadow(p, wl, cutters, sink.recording(), &sh);
    if (sh.visible && !(portals && sh.first_is_element)) {  // through elements: portal samples
      const float w = power_heuristic(light_pdf, cos_l * kInvPi);
      sink.light(sky.radiance(wl) * sh.attenuation * (cos_l * w / light_pdf), sh.crossed.data(), sh.crossed_count,
                 sky_source(wl));
    }
  }
  if (!scene_.suns.empty()) {
    // The sun is found by this sample alone, through elements too (portal samples aim at the sky).
    const float u_pick = samples ? samples->get1d(PathSamples::kSensorSunPick) : rng.uniform();
    const Vec2 u_disk = samples ? samples->get2d(PathSamples::kSensorSun) : next2(rng);
    const SunLights::Sample sun = scene_.suns.sample(u_pick, u_disk);
    const float cos_s = sun.direction.dot(n);
    Shadow sh;
    if (cos_s > 0.0f) shadow(p, sun.direction, cutters, sink.recording(), &sh);
    if (cos_s > 0.0f && sh.visible)
      sink.light(sun.illuminance * sh.attenuation * cos_s, sh.crossed.data(), sh.crossed_count,
                 sun_source(sun.index) | (patches_ ? AnnualSources::kDirect : 0));
  }
  PathState st;
  st.beta = Rgb::Constant(kPi);
  st.portals = portals;
  st.from_sensor = true;
  st.vertex = p;
  st.vertex_normal = n;
  if (portals) {
    PathState from_sensor = st;
    from_sensor.beta = Rgb::Ones();
    from_sensor.portal_exclusive = true;
    auto cosine = [&](const Vec3& d, float* pdf) {
      const float c = std::max(0.0f, d.dot(n));
      *pdf = c * kInvPi;
      return Rgb::Constant(c);
    };
    if (samples) {
      // Stratified over the group's samples, aimed by the sensor's view of the elements, and
      // uniform in each element's solid angle.
      if (portal_selection_.size() != scene_.sensors.size())
        throw std::logic_error("PathTracer: prepare_portal_selection() must run before recording stratified paths");
      const size_t count = stratified_sensor_portals_;
      for (size_t j = 0; j < count; ++j) {
        const auto [u, v] = samples->portal(j, count);
        const PortalSelection::Choice c = portal_selection_[i].choose(u);
        const PortalAim aim = aim_at_element(c.element, Vec2(c.remainder, v),
                                             static_cast<float>(count * c.probability), true,
                                             p, n);
        sample_portal(aim, p, n, from_sensor, rng, cosine, sink);
      }
    } else {
      SensorPortal chosen[kSensorPortals];
      sensor_portals(i, path, chosen);
      for (const SensorPortal& sp : chosen)
        sample_portal(aim_at_element(sp.element, sp.uv, sp.samples_per_path, false, p, n), p, n, from_sensor, rng,
                      cosine, sink);
    }
  }
  const Vec3 local =
      square_to_cosine_hemisphere(samples ? samples->get2d(PathSamples::kFirstBounce) : next2(rng));
  st.prev_pdf = square_to_cosine_hemisphere_pdf(local);
  if (st.prev_pdf <= 0.0f) return;
  st.samples = samples;
  trace(p, frame.to_world(local), st, cutters, rng, sink);
}

uint16_t PathTracer::sky_source(const Vec3& dir) const {
  return patches_ ? static_cast<uint16_t>(patches_->patch_of(dir)) : 0;
}

uint16_t PathTracer::sun_source(int index) const {
  return patches_ ? static_cast<uint16_t>(patches_->count() + index) : 0;
}

PathTracer::DirectSun PathTracer::direct_sun_through_openings(size_t sensor, const Vec3& direction) const {
  DirectSun out;
  const Vec3& n = scene_.sensors.normals[sensor];
  out.cosine = direction.dot(n);
  if (!(out.cosine > 0.0f)) return out;
  Shadow sh;
  shadow(scene_.sensors.points[sensor] + kRayEpsilon * n, direction, &openings_, false, &sh);
  out.visible = sh.visible;
  if (sh.visible) out.attenuation = luminance(sh.attenuation);
  return out;
}

PathTracer::DirectSun PathTracer::direct_sun(size_t sensor, const Vec3& direction) const {
  DirectSun out;
  const Vec3& n = scene_.sensors.normals[sensor];
  out.cosine = direction.dot(n);
  if (!(out.cosine > 0.0f)) return out;
  Shadow sh;
  shadow(scene_.sensors.points[sensor] + kRayEpsilon * n, direction, nullptr, true, &sh);
  if (!sh.visible) return out;
  out.visible = true;
  out.attenuation = luminance(sh.attenuation);
  out.crossed.assign(sh.crossed.begin(), sh.crossed.begin() + sh.crossed_count);
  return out;
}

float PathTracer::sensor_sample(size_t sensor, const PathSamples* samples, Rng& rng) const {
  Sink sink = Sink::sum();
  trace_sensor(sensor, 0, samples, rng, &openings_, sink);
  return static_cast<float>(sink.total());
}

void PathTracer::sensor_sample_by_source(size_t sensor, const PathSamples* samples, Rng& rng,
                                         std::vector<SourceLight>* out) const {
  Sink sink = Sink::by_source(out);
  trace_sensor(sensor, 0, samples, rng, &openings_, sink);
}

void PathTracer::record_sensor_path(size_t sensor, size_t path, const PathSamples* samples, Rng& rng,
                                    SensorRecord* record) const {
  record->path_key = sensor << 32 ^ path;
  Sink sink = Sink::record(record, &scene_.domain.elements());
  trace_sensor(sensor, path, samples, rng, nullptr, sink);
  record->end_path();
}

void PathTracer::prepare_portal_selection(int threads, SensorRange range) {
  range = range.within(scene_.sensors.size());
  if (portals_.empty() || (portal_selection_.size() == scene_.sensors.size() && prepared_.begin <= range.begin &&
                           range.end <= prepared_.end))
    return;
  std::vector<PortalShape> shapes(portals_.size());
  for (size_t k = 0; k < portals_.size(); ++k) {
    const Portal& p = portals_[k];
    PortalShape& shape = shapes[k];
    shape.corner = p.corner, shape.u = p.u, shape.v = p.v, shape.normal = p.normal, shape.curved = p.curved;
    if (p.curved) {
      const PortalPoint middle = portal_point(static_cast<int>(k), Vec2(0.5f, 0.5f));
      shape.center = middle.position;
      shape.normal = middle.normal;
      shape.area = p.size.x() * p.size.y() * middle.area_ratio;
    }
  }
  portal_selection_.assign(scene_.sensors.size(), PortalSelection());  // the others' stay empty
  prepared_ = range;
  parallel_tasks(range.size(), threads, nullptr, [&](size_t local) {
    const size_t i = range.begin + local;
    const Vec3& n = scene_.sensors.normals[i];
    const Vec3 p = scene_.sensors.points[i] + kRayEpsilon * n;
    std::vector<double> weights(shapes.size());
    for (size_t k = 0; k < shapes.size(); ++k) weights[k] = portal_view_weight(p, n, shapes[k]);
    portal_selection_[i] = PortalSelection(weights);
  });
}

size_t PathTracer::portal_selection_bytes() const {
  size_t bytes = 0;
  for (const PortalSelection& s : portal_selection_) bytes += s.memory_bytes();
  return bytes;
}

void PathTracer::check_sensors(SensorRange range) const {
  // A sensor inside a closed solid sees only the back of faces and no opening domain in any direction.
  constexpr int kProbes = 64;
  range = range.within(scene_.sensors.size());
  for (size_t i = range.begin; i < range.end; ++i) {
    const Vec3& p = scene_.sensors.points[i];
    bool inside = true;
    for (int k = 0; k < kProbes && inside; ++k) {
      const float z = 1.0f - (2.0f * k + 1.0f) / kProbes;  // Fibonacci sphere
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const float phi = 2.39996323f * k;
      const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
      const Hit h = rays_->intersect(p, d, 0.0f, kInfinity, &openings_);
      if (!h.valid()) {
        inside = false;
        break;
      }
      const Surface s = surface(h);
      inside = !s.inner_face() && d.dot(s.normal) > 0.0f;
    }
    if (inside) {
      std::ostringstream m;
      const Vec3d at = scene_.site.to_site(p);  // where the user put it
      m.precision(10);
      m << "sensor " << i << " at (" << at.x() << ", " << at.y() << ", " << at.z() << ") is inside geometry: every direction from it meets the back "
        << "of a face";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace fenestra
