#include "trace/portal_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sampling/spherical_rectangle.h"
#include "sampling/warp.h"
#include "trace/parallel.h"
#include "trace/replicates.h"
#include "trace/scene_hits.h"
#include "util/rng.h"

namespace fenestra {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Steradians: below, an element is sampled by area (its solid angle's formula loses precision,
// and area sampling is as good there).
constexpr double kMinSolidAngle = 1e-4;
constexpr float kCosineFloor = 0.01f;

float radical_inverse(uint32_t index, uint32_t base) {
  const float inv = 1.0f / static_cast<float>(base);
  float result = 0.0f, digit = inv;
  for (; index > 0; index /= base, digit *= inv) result += static_cast<float>(index % base) * digit;
  return result;
}

}  // namespace

PortalSampler::PortalSampler(const OpeningDomain& domain, const RenderSettings& render)
    : domain_(domain), seed_(render.seed), paths_per_sensor_(static_cast<size_t>(render.paths_per_sensor)) {
  for (const Element& e : domain_.elements()) {
    const Panel& panel = domain_.panels()[e.panel];
    portals_.push_back({e.corners[0], e.width() * panel.u_axis, e.height() * panel.v_axis, panel.normal, e.panel,
                        panel.curved(), {e.u0, e.v0}, {e.width(), e.height()}});
  }
  by_panel_ = render.sampler == RenderSettings::Sampler::kSobol && !portals_.empty();
  build_panels();
}

void PortalSampler::build_panels() {
  std::vector<int> index_of_panel(domain_.panels().size(), -1);
  for (size_t k = 0; k < portals_.size(); ++k) {
    const int panel = portals_[k].panel;
    if (index_of_panel[panel] < 0) {
      index_of_panel[panel] = static_cast<int>(panels_.size());
      panels_.push_back({});
      panels_.back().panel = panel;
      panels_.back().flat = !domain_.panels()[panel].curved();
    }
    panels_[index_of_panel[panel]].portals.push_back(static_cast<int>(k));
  }
  float running = 0.0f;
  for (PortalPanel& p : panels_) {
    const Panel& panel = domain_.panels()[p.panel];
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
  if (!panels_.empty()) panels_.back().share_end = 1.0f;
  bool all_flat = true;
  for (const PortalPanel& p : panels_) all_flat = all_flat && p.flat;
  stratified_sensor_portals_ = all_flat && !domain_.has_thick_walls() ? kStratifiedSensorPortals : kSensorPortals;
}

void PortalSampler::sensor_portals(size_t sensor, size_t path, SensorPortal* out) const {
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
  const size_t group_paths = replicate_size(group, paths_per_sensor_);
  const uint64_t key = mix_seed(mix_seed(seed_, sensor), 0x9047A1 + group);
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

PortalSampler::Point PortalSampler::portal_point(int k, const Vec2& uv) const {
  const Portal& portal = portals_[k];
  Point out;
  if (!portal.curved) {
    out.position = portal.corner + uv.x() * portal.u + uv.y() * portal.v;
    out.normal = portal.normal;
    out.at = domain_.panel_point(portal.panel, out.position);
    return out;
  }
  out.at = {portal.cell.u + uv.x() * portal.size.x(), portal.cell.v + uv.y() * portal.size.y()};
  const DomainSurfacePoint s = domain_.surface_at(portal.panel, out.at.u, out.at.v);
  out.position = s.position;
  out.normal = s.outward;
  out.area_ratio = s.area_ratio;
  return out;
}

PortalSampler::Aim PortalSampler::sample(float u_pick, const Vec2& uv, const Vec3& x, const Vec3& n) const {
  if (by_panel_) return aim_from_vertex(u_pick, uv, x);
  const int k = std::min(static_cast<int>(u_pick * portals_.size()), static_cast<int>(portals_.size()) - 1);
  return aim_at_element(k, uv, 1.0f / static_cast<float>(portals_.size()), false, x, n);
}

float PortalSampler::pdf(int k, const PanelPoint& at, const Vec3& from, float distance, const Vec3& dir) const {
  const int panel = domain_.elements()[k].panel;
  const PortalPanel* portal_panel = nullptr;
  if (by_panel_) {
    for (const PortalPanel& p : panels_)
      if (p.panel == panel) portal_panel = &p;
    if (!portal_panel) return 0.0f;
    if (portal_panel->flat) {  // aim_from_vertex: uniform in the solid angle of the panel's rectangle
      const double omega = rectangle_solid_angle(from, portal_panel->corner, portal_panel->u, portal_panel->v);
      if (omega > kMinSolidAngle) return portal_panel->share / static_cast<float>(omega);
    }
  }
  // An element chosen among all (or among its panel's), then a uniform point of its square in panel
  // coordinates, converted to solid angle (on a curved panel, through the surface's area there).
  const Portal& portal = portals_[k];
  Vec3 normal = portal.normal;
  float area_ratio = 1.0f;
  if (portal.curved) {
    const DomainSurfacePoint s = domain_.surface_at(portal.panel, at.u, at.v);
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

float PortalSampler::sample_pdf(const Aim& aim, float distance, float cos_at) const {
  if (aim.solid_angle_pdf != 0.0f) return aim.solid_angle_pdf;
  const Vec2& size = portals_[aim.portal].size;
  return aim.selection * distance * distance / (size.x() * size.y() * aim.point.area_ratio * cos_at);
}

PortalSampler::Aim PortalSampler::aim_at_element(int k, const Vec2& uv, float selection, bool by_solid_angle,
                                                 const Vec3& x, const Vec3& n) const {
  const Portal& square = portals_[k];
  Aim aim;
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
    aim.point.at = domain_.panel_point(square.panel, aim.point.position);
    aim.solid_angle_pdf = selection * bilinear_pdf(warped, w) / static_cast<float>(omega);
  } else {
    aim.point = portal_point(k, uv);
  }
  return aim;
}

PortalSampler::Aim PortalSampler::aim_from_vertex(float u_pick, const Vec2& uv, const Vec3& x) const {
  // A panel by its share of the elements, then a point uniform in the solid angle of the
  // rectangle its elements span (flat panels), or an element of it and a point by area.
  size_t p = 0;
  while (p + 1 < panels_.size() && u_pick >= panels_[p].share_end) ++p;
  const PortalPanel& panel = panels_[p];
  const float begin = p == 0 ? 0.0f : panels_[p - 1].share_end;
  const float remainder = std::clamp((u_pick - begin) / (panel.share_end - begin), 0.0f, 0.99999994f);
  Aim aim;
  aim.panel = panel.panel;
  const double omega = panel.flat ? rectangle_solid_angle(x, panel.corner, panel.u, panel.v) : 0.0;
  if (omega > kMinSolidAngle) {
    aim.point.position = SphericalRectangle(x, panel.corner, panel.u, panel.v).sample(uv);
    aim.point.normal = domain_.panels()[panel.panel].normal;
    aim.point.at = domain_.panel_point(panel.panel, aim.point.position);
    aim.solid_angle_pdf = panel.share / static_cast<float>(omega);
    return aim;
  }
  const size_t count = panel.portals.size();
  aim.portal = panel.portals[std::min(count - 1, static_cast<size_t>(remainder * count))];
  aim.selection = panel.share / static_cast<float>(count);
  aim.point = portal_point(aim.portal, uv);
  return aim;
}

PortalSampler::Aim PortalSampler::sensor_stratified(size_t sensor, size_t count, uint32_t u, float v, const Vec3& x,
                                                    const Vec3& n) const {
  const PortalSelection::Choice c = selection_[sensor].choose(u);
  return aim_at_element(c.element, Vec2(c.remainder, v), static_cast<float>(count * c.probability), true, x, n);
}

void PortalSampler::prepare_selection(const Sensors& sensors, int threads, SensorRange range) {
  range = range.within(sensors.points.size());
  if (portals_.empty() ||
      (selection_.size() == sensors.points.size() && prepared_.begin <= range.begin && range.end <= prepared_.end))
    return;
  std::vector<PortalShape> shapes(portals_.size());
  for (size_t k = 0; k < portals_.size(); ++k) {
    const Portal& p = portals_[k];
    PortalShape& shape = shapes[k];
    shape.corner = p.corner, shape.u = p.u, shape.v = p.v, shape.normal = p.normal, shape.curved = p.curved;
    if (p.curved) {
      const Point middle = portal_point(static_cast<int>(k), Vec2(0.5f, 0.5f));
      shape.center = middle.position;
      shape.normal = middle.normal;
      shape.area = p.size.x() * p.size.y() * middle.area_ratio;
    }
  }
  selection_.assign(sensors.points.size(), PortalSelection());  // the others' stay empty
  prepared_ = range;
  parallel_tasks(range.size(), threads, nullptr, [&](size_t local) {
    const size_t i = range.begin + local;
    const Vec3& n = sensors.normals[i];
    const Vec3 p = sensors.points[i] + kRayEpsilon * n;
    std::vector<double> weights(shapes.size());
    for (size_t k = 0; k < shapes.size(); ++k) weights[k] = portal_view_weight(p, n, shapes[k]);
    selection_[i] = PortalSelection(weights);
  });
}

size_t PortalSampler::selection_bytes() const {
  size_t bytes = 0;
  for (const PortalSelection& s : selection_) bytes += s.memory_bytes();
  return bytes;
}

}  // namespace fenestra
