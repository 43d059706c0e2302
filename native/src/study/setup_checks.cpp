#include "study/setup_checks.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "scene/scene.h"
#include "solve/goals.h"
#include "trace/nearest_surface.h"
#include "trace/ray_scene.h"
#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr int kRays = 64;               // directions per sensor, spread over the sphere
constexpr double kOutdoors = 0.5;       // a sensor seeing the sky in this share of its directions is outdoors
constexpr int kGapRays = 2;             // ... sees the sky through a gap when this many of its rays escape
constexpr float kDownward = -0.5f;      // a sensor normal's z below this faces downward
constexpr float kLift = 1e-3f;          // m: rays start this far off the sensor, along its normal
constexpr size_t kMaxPanels = 50;       // flat domain panels checked for their side, the largest first
constexpr size_t kSamplesPerPanel = 3;  // points of a panel the sensors look at
constexpr size_t kNamedSensors = 3;     // sensors a message names
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Unit vectors spread evenly over the sphere (a Fibonacci lattice), turned off the axes so that
// none runs exactly along a box room's edges or corners.
std::vector<Vec3> directions() {
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0)), tilt = 7.0 * 3.14159265358979323846 / 180.0;
  std::vector<Vec3> out;
  for (int i = 0; i < kRays; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kRays, r = std::sqrt(1.0 - z * z), phi = (i + 0.5) * golden + 0.3;
    const double x = r * std::cos(phi), y = r * std::sin(phi);
    out.emplace_back(float(x), float(std::cos(tilt) * y - std::sin(tilt) * z), float(std::sin(tilt) * y + std::cos(tilt) * z));
  }
  return out;
}

// Indices of the sensors the rays look at: all, or kMaxCheckedSensors evenly spaced.
std::vector<int> sampled(size_t count) {
  std::vector<int> out;
  if (count <= kMaxCheckedSensors) {
    for (size_t i = 0; i < count; ++i) out.push_back(static_cast<int>(i));
    return out;
  }
  for (size_t k = 0; k < kMaxCheckedSensors; ++k)
    out.push_back(static_cast<int>(std::llround(static_cast<double>(k) * (count - 1) / (kMaxCheckedSensors - 1))));
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// A ray's start off a point: kLift, or more where the point's coordinates are too large for
// single precision to resolve kLift.
float lift_at(const Vec3& p) { return std::max(kLift, 4.0f * std::numeric_limits<float>::epsilon() * p.cwiseAbs().maxCoeff()); }

// A position as the user gave it (the scene's input coordinates).
std::string point_text(const Scene& scene, const Vec3& local) {
  const Vec3d p = scene.site.to_site(local);
  return "(" + decimal_text(p.x(), "%.2f") + ", " + decimal_text(p.y(), "%.2f") + ", " + decimal_text(p.z(), "%.2f") + ")";
}

// "sensor 4 at (1.00, 2.00, 0.80)" or "sensors 0 (..), 1 (..), 2 (..) and 13 more".
std::string sensors_text(const Scene& scene, const std::vector<int>& sensors) {
  std::ostringstream s;
  s << (sensors.size() == 1 ? "sensor " : "sensors ");
  for (size_t k = 0; k < std::min(sensors.size(), kNamedSensors); ++k)
    s << (k ? ", " : "") << sensors[k] << (sensors.size() == 1 ? " at " : " ") << point_text(scene, scene.sensors.points[sensors[k]]);
  if (sensors.size() > kNamedSensors) s << " and " << sensors.size() - kNamedSensors << " more";
  return s.str();
}

// "3 of 40 sensors", or "3 of the 10 000 sensors checked (of 90 000)".
std::string of_text(size_t count, size_t total, size_t checked) {
  std::ostringstream s;
  if (checked < total)
    s << count << " of the " << checked << " sensors checked (of " << total << ")";
  else
    s << count << " of " << total << " sensor" << (total == 1 ? "" : "s");
  return s.str();
}

// The verb for `count` sensors: "is" / "are", "sees" / "see".
const char* verb(size_t count, const char* one, const char* many) { return count == 1 ? one : many; }

void zero_goals(const Scene& scene, std::vector<SetupWarning>* out) {
  if (!scene.sensors.climate_goals.empty()) return;
  const GivenGoals g = given_goals(scene);
  SetupWarning w;
  w.kind = SetupWarning::Kind::ZeroGoals;
  w.total = w.checked = scene.sensors.size();
  for (Eigen::Index i = 0; i < g.level.size(); ++i) {
    if (!(g.weight[i] > 0.0)) continue;
    if (g.level[i] > 0.0 || g.lower[i] > 0.0) return;
    w.sensors.push_back(static_cast<int>(i));
  }
  if (w.sensors.empty()) return;  // no goal at all: the solve refuses it (require_goals)
  w.message = std::string(w.sensors.size() == 1 ? "the only sensor goal is 0 (" : "all ") +
              (w.sensors.size() == 1 ? "" : std::to_string(w.sensors.size()) + " sensor goals are 0 (") +
              (scene.sensors.uniform_goals.empty() ? "sensors.goals" : "goals.uniform") +
              "): the solve opens nothing and reports 0 % error; set a goal above 0";
  out->push_back(std::move(w));
}

// Sensors outdoors, and sensors seeing the sky through gaps that are not opening domain.
void open_sky(const Scene& scene, const RayScene& rays, std::vector<SetupWarning>* out) {
  const std::vector<int> chosen = sampled(scene.sensors.size());
  const std::vector<Vec3> dirs = directions();
  std::vector<uint64_t> escaped(chosen.size(), 0);  // one bit per direction
  static_assert(kRays <= 64, "one bit per direction");
  tbb::parallel_for(size_t(0), chosen.size(), [&](size_t k) {
    const Vec3& p = scene.sensors.points[chosen[k]];
    const Vec3& n = scene.sensors.normals[chosen[k]];
    const Vec3 origin = p + lift_at(p) * n;
    uint64_t bits = 0;
    for (int j = 0; j < kRays; ++j)
      if (!rays.intersect(origin, dirs[j], 0.0f, kInfinity, nullptr).valid()) bits |= uint64_t(1) << j;
    escaped[k] = bits;
  });
  SetupWarning outdoors, gaps;
  outdoors.kind = SetupWarning::Kind::Outdoors;
  gaps.kind = SetupWarning::Kind::OpenRoom;
  double share_sum = 0.0;
  Eigen::Vector3d way = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < chosen.size(); ++k) {
    const Vec3& n = scene.sensors.normals[chosen[k]];
    int count = 0, facing = 0, facing_escaped = 0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int j = 0; j < kRays; ++j) {
      const bool e = (escaped[k] >> j) & 1;
      const bool front = n.dot(dirs[j]) > 0.0f;
      count += e, facing += front, facing_escaped += e && front;
      if (e) sum += dirs[j].cast<double>();
    }
    const double sphere = static_cast<double>(count) / kRays;
    const double hemisphere = static_cast<double>(facing_escaped) / std::max(facing, 1);
    if (sphere >= kOutdoors || hemisphere >= kOutdoors) {
      outdoors.sensors.push_back(chosen[k]);
    } else if (count >= kGapRays) {
      gaps.sensors.push_back(chosen[k]);
      share_sum += sphere;
      way += sum;
    }
  }
  const size_t total = scene.sensors.size();
  if (!outdoors.sensors.empty()) {
    outdoors.total = total, outdoors.checked = chosen.size();
    outdoors.message = of_text(outdoors.sensors.size(), total, chosen.size()) + " " +
                       verb(outdoors.sensors.size(), "is", "are") +
                       " outdoors or outside every room (they see the sky in most directions): " +
                       sensors_text(scene, outdoors.sensors) +
                       "; no opening changes their light much, so their error stays large: move them into the rooms "
                       "(sensors.points), or remove them";
    out->push_back(std::move(outdoors));
  }
  if (!gaps.sensors.empty()) {
    gaps.total = total, gaps.checked = chosen.size();
    gaps.share = share_sum / static_cast<double>(gaps.sensors.size());
    if (way.norm() > 0.0) way.normalize();
    gaps.direction = way.cast<float>();
    const std::string where = way.z() > 0.5    ? "mostly upward: a missing roof or ceiling?"
                              : way.z() < -0.5 ? "mostly downward: a missing floor?"
                                               : "mostly sideways: a missing wall, a door or window that is not "
                                                 "opening domain?";
    gaps.message = of_text(gaps.sensors.size(), total, chosen.size()) + " " + verb(gaps.sensors.size(), "sees", "see") +
                   " the sky through gaps that are not opening domain (" + decimal_text(100.0 * gaps.share, "%.0f") +
                   " % of their directions on average, " + where + "): " + sensors_text(scene, gaps.sensors) +
                   "; daylight through the gaps counts toward the goals: close the model there if the room is closed";
    out->push_back(std::move(gaps));
  }
}

void downward(const Scene& scene, std::vector<SetupWarning>* out) {
  SetupWarning w;
  w.kind = SetupWarning::Kind::Downward;
  w.total = w.checked = scene.sensors.size();
  for (size_t i = 0; i < scene.sensors.size(); ++i)
    if (scene.sensors.normals[i].z() < kDownward) w.sensors.push_back(static_cast<int>(i));
  if (w.sensors.empty()) return;
  w.message = of_text(w.sensors.size(), w.total, w.total) + " " + verb(w.sensors.size(), "faces", "face") +
              " downward (normal z below " + decimal_text(kDownward, "%.1f") +
              "): " + sensors_text(scene, w.sensors) +
              "; a sensor measures the light on the side its normal points to, here the light from below: if they "
              "should face up, flip their normals (sensors.normals)";
  out->push_back(std::move(w));
}

// Flat panels seen by more of the sensors outside (the side of their plane away from the room
// the solver takes: OpeningDomain::orient) than inside.
void domain_sides(const Scene& scene, const RayScene& rays, std::vector<SetupWarning>* out) {
  const std::vector<Panel>& panels = scene.domain.panels();
  std::vector<int> order;
  for (size_t i = 0; i < panels.size(); ++i)
    if (!panels[i].curved() && !panels[i].triangles.empty()) order.push_back(static_cast<int>(i));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return panels[a].area > panels[b].area; });
  if (order.size() > kMaxPanels) order.resize(kMaxPanels);
  const std::vector<int> chosen = sampled(scene.sensors.size());
  const Mesh& mesh = scene.mesh;
  SetupWarning w;
  w.kind = SetupWarning::Kind::DomainSide;
  w.total = scene.sensors.size(), w.checked = chosen.size();
  std::ostringstream parts;
  for (int index : order) {
    const Panel& panel = panels[index];
    // The room's side of the plane, as the solver took it: away from `outward`.
    const float room = panel.outward.dot(panel.normal) > 0.0f ? -1.0f : 1.0f;
    auto side = [&](const Vec3& p) {
      const float d = (p - panel.origin).dot(panel.normal);
      return d > 0.0f ? 1.0f : d < 0.0f ? -1.0f : 0.0f;
    };
    std::vector<uint32_t> largest(panel.triangles);
    std::stable_sort(largest.begin(), largest.end(),
                     [&](uint32_t a, uint32_t b) { return mesh.area_normal(a).norm() > mesh.area_normal(b).norm(); });
    if (largest.size() > kSamplesPerPanel) largest.resize(kSamplesPerPanel);
    std::vector<Vec3> targets;
    for (uint32_t t : largest) targets.push_back((mesh.vertex(t, 0) + mesh.vertex(t, 1) + mesh.vertex(t, 2)) / 3.0f);
    std::atomic<int> seen_room{0}, seen_outside{0};
    tbb::parallel_for(size_t(0), chosen.size(), [&](size_t k) {
      const Vec3& p = scene.sensors.points[chosen[k]];
      const float s = side(p);
      if (s == 0.0f) return;
      const Vec3 origin = p + lift_at(p) * scene.sensors.normals[chosen[k]];
      for (const Vec3& target : targets) {
        const Vec3 d = target - origin;
        const float length = d.norm();
        // Stop short of the panel itself, by more than single precision resolves at the target.
        const float stop = length - std::max(1e-4f * length, lift_at(target));
        if (!(stop > 0.0f)) continue;
        if (!rays.intersect(origin, d / length, 0.0f, stop, nullptr).valid()) {
          ++(s == room ? seen_room : seen_outside);
          break;
        }
      }
    });
    if (seen_outside.load() <= seen_room.load()) continue;
    SetupWarning::Panel flagged;
    flagged.panel = index;
    flagged.seen_from_outside = seen_outside.load();
    for (const Vec3& p : scene.sensors.points) flagged.on_room_side += side(p) == room;
    std::vector<int> groups;
    for (uint32_t t : panel.triangles)
      if (t < mesh.triangle_group.size() && mesh.triangle_group[t] >= 0) groups.push_back(mesh.triangle_group[t]);
    std::sort(groups.begin(), groups.end());
    groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
    for (int g : groups) flagged.groups.push_back(mesh.group_names[g]);
    Vec3 centre = Vec3::Zero();
    double area = 0.0;
    for (uint32_t t : panel.triangles) {
      const float a = mesh.area_normal(t).norm();
      centre += a * (mesh.vertex(t, 0) + mesh.vertex(t, 1) + mesh.vertex(t, 2)) / 3.0f;
      area += a;
    }
    if (area > 0.0) centre /= static_cast<float>(area);
    parts << (w.panels.empty() ? "" : "; ") << "panel " << index << " (" << panel.label << "; "
          << decimal_text(panel.area, "%.3g") << " m2 about " << point_text(scene, centre) << ") is seen by "
          << flagged.seen_from_outside << " sensor" << (flagged.seen_from_outside == 1 ? "" : "s")
          << " from one side, but " << flagged.on_room_side << " of "
          << scene.sensors.size() << " sensors " << verb(static_cast<size_t>(flagged.on_room_side), "lies", "lie")
          << " on the other side of its plane, which the solver takes for the room";
    w.panels.push_back(std::move(flagged));
  }
  if (w.panels.empty()) return;
  w.message = "opening domain: " + parts.str() +
              ": a thick wall would be measured and cut toward the sensors that see it; solve the rooms on either side "
              "as separate studies, or give opening_domain.thickness 0 with single-face walls";
  out->push_back(std::move(w));
}


// Sensors within kNearSurface of a face that cuts through their hemisphere: the opening domain's
// first (OnDomain), any other's next (NearSurface). A face parallel to the sensor and behind it
// (the floor under a workplane sensor, a table) is no problem.
void near_surfaces(const Scene& scene, std::vector<SetupWarning>* out) {
  const Mesh& mesh = scene.mesh;
  std::vector<uint8_t> domain(mesh.triangle_count(), 0);
  for (const Panel& p : scene.domain.panels())
    for (uint32_t t : p.triangles) domain[t] = 1;
  const NearestSurface surfaces(mesh);
  const size_t total = scene.sensors.size();
  std::vector<uint8_t> found(total, 0);  // 1 on the domain, 2 on another surface
  tbb::parallel_for(size_t(0), total, [&](size_t i) {
    const Vec3& p = scene.sensors.points[i];
    const Vec3& n = scene.sensors.normals[i];
    const float radius = kNearSurface;  // local coordinates: floats resolve far below a centimetre
    if (nearest_in_view(surfaces, mesh, p, n, radius, &domain).found())
      found[i] = 1;
    else if (nearest_in_view(surfaces, mesh, p, n, radius).found())
      found[i] = 2;
  });
  const std::string within = decimal_text(kNearSurface, "%.2f") + " m";
  for (const auto kind : {SetupWarning::Kind::OnDomain, SetupWarning::Kind::NearSurface}) {
    SetupWarning w;
    w.kind = kind;
    w.total = w.checked = total;
    const uint8_t mark = kind == SetupWarning::Kind::OnDomain ? 1 : 2;
    for (size_t i = 0; i < total; ++i)
      if (found[i] == mark) w.sensors.push_back(static_cast<int>(i));
    if (w.sensors.empty()) continue;
    const std::string head = of_text(w.sensors.size(), total, total) + " " + verb(w.sensors.size(), "lies", "lie");
    if (kind == SetupWarning::Kind::OnDomain)
      w.message = head + " on the opening domain (within " + within + " of it): " + sensors_text(scene, w.sensors) +
                  "; half their view is the opening itself, so their light is nothing a person in the room would "
                  "read and the solve chases it: move them into the room, at least " + within +
                  " off the walls (sensors.points), or remove them";
    else
      w.message = head + " on a wall, ceiling or other surface (within " + within + " of it): " +
                  sensors_text(scene, w.sensors) +
                  "; part of their view is inside that surface, so their light depends on millimetres: move them "
                  "at least " + within + " off every surface but the floor under them (sensors.points)";
    out->push_back(std::move(w));
  }
}

}  // namespace

const char* setup_kind_name(SetupWarning::Kind kind) {
  switch (kind) {
    case SetupWarning::Kind::ZeroGoals: return "zero_goals";
    case SetupWarning::Kind::Outdoors: return "outdoors";
    case SetupWarning::Kind::OpenRoom: return "open_room";
    case SetupWarning::Kind::Downward: return "downward";
    case SetupWarning::Kind::DomainSide: return "domain_side";
    case SetupWarning::Kind::OnDomain: return "on_domain";
    case SetupWarning::Kind::NearSurface: return "near_surface";
  }
  return "unknown";
}

SetupStage setup_stage(const std::string& name) {
  static const std::map<std::string, SetupStage> kNames = {
      {"solve", SetupStage::Solve}, {"contributions", SetupStage::Contributions}, {"evaluate", SetupStage::Evaluate}};
  const auto it = kNames.find(name);
  if (it == kNames.end())
    throw std::invalid_argument("setup checks: unknown command '" + name.substr(0, 80) +
                                "' (solve, contributions or evaluate)");
  return it->second;
}

std::vector<SetupWarning> check_setup(const Scene& scene, SetupStage stage) {
  std::vector<SetupWarning> out;
  if (scene.sensors.size() == 0) return out;
  if (stage == SetupStage::Solve) zero_goals(scene, &out);
  const bool rays_needed = scene.mesh.triangle_count() > 0;
  std::unique_ptr<RayScene> rays;
  if (rays_needed) rays = std::make_unique<RayScene>(scene.mesh, Mesh());  // every element closed
  if (stage != SetupStage::Evaluate && rays) open_sky(scene, *rays, &out);
  downward(scene, &out);
  if (rays) domain_sides(scene, *rays, &out);
  if (rays_needed) near_surfaces(scene, &out);
  return out;
}

std::vector<std::string> setup_messages(const Scene& scene, const std::vector<SetupWarning>& warnings, bool strict) {
  std::vector<std::string> messages;
  for (const SetupWarning& w : warnings) messages.push_back(w.message);
  if (strict && !messages.empty()) {
    std::string text = "scene '" + scene.source + "': the setup checks found " + std::to_string(messages.size()) +
                       " problem" + (messages.size() == 1 ? "" : "s") + " (strict)";
    for (const std::string& m : messages) text += "; " + m;
    throw std::invalid_argument(text);
  }
  return messages;
}

}  // namespace fenestra
