#include "trace/kept_cut.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trace/parallel.h"
#include "trace/path_samples.h"
#include "trace/path_tracer.h"
#include "trace/replicates.h"
#include "util/rng.h"

namespace fenestra {
namespace {

// Meters around a region: rays leave surfaces kRayEpsilon off them, and corners are rounded to
// floats once in each frame.
constexpr float kRegionMargin = 1e-3f;
bool same_cutter(const Cutter& a, const Cutter& b) {
  return a.origin == b.origin && a.u_axis == b.u_axis && a.v_axis == b.v_axis && a.normal == b.normal &&
         a.width == b.width && a.height == b.height && a.depth_back == b.depth_back &&
         a.depth_front == b.depth_front && a.chart == b.chart && a.u0 == b.u0 && a.u1 == b.u1 && a.v0 == b.v0 &&
         a.v1 == b.v1;
}

// Rectangles of one panel share their axes exactly; their origins may lie a rounding apart along
// the normal, which the regions' depth takes in.
bool same_frame(const Cutter& a, const Cutter& b) {
  return a.u_axis == b.u_axis && a.v_axis == b.v_axis && a.normal == b.normal &&
         std::abs((b.origin - a.origin).dot(a.normal)) < kRegionMargin;
}

ChangedRegion region_in(const Cutter& frame, float u0, float u1, float v0, float v1, float n0, float n1) {
  ChangedRegion r;
  r.origin = frame.origin, r.u_axis = frame.u_axis, r.v_axis = frame.v_axis, r.normal = frame.normal;
  r.lo[0] = u0 - kRegionMargin, r.hi[0] = u1 + kRegionMargin;
  r.lo[1] = v0 - kRegionMargin, r.hi[1] = v1 + kRegionMargin;
  r.lo[2] = n0 - kRegionMargin, r.hi[2] = n1 + kRegionMargin;
  return r;
}

ChangedRegion whole(const Cutter& c) { return region_in(c, 0.0f, c.width, 0.0f, c.height, -c.depth_back, c.depth_front); }

// The slabs holding what differs between two cutters of one frame (a's): each side that moved,
// between its two positions, along the whole of both rectangles' other extent; and the planes of
// all four sides, before and after, through the wall: a side's reveal face is stretched when a
// side across it moves, and every corner is computed from the cutter's origin and extent, so a
// face that did not move may still lie an ulp away (a surface met on another triangle, or on one an
// ulp away, need not give the same path to the last bit).
void add_moved_sides(const Cutter& a, const Cutter& b, std::vector<ChangedRegion>* out) {
  const Vec3 d = b.origin - a.origin;
  const float a_u[2] = {0.0f, a.width}, a_v[2] = {0.0f, a.height};
  const float b_u[2] = {d.dot(a.u_axis), d.dot(a.u_axis) + b.width}, b_v[2] = {d.dot(a.v_axis), d.dot(a.v_axis) + b.height};
  const float off = std::abs(d.dot(a.normal));
  const float n0 = -std::max(a.depth_back, b.depth_back) - off, n1 = std::max(a.depth_front, b.depth_front) + off;
  const float u_lo = std::min(a_u[0], b_u[0]), u_hi = std::max(a_u[1], b_u[1]);
  const float v_lo = std::min(a_v[0], b_v[0]), v_hi = std::max(a_v[1], b_v[1]);
  for (int k = 0; k < 2; ++k) {
    out->push_back(region_in(a, std::min(a_u[k], b_u[k]), std::max(a_u[k], b_u[k]), v_lo, v_hi, n0, n1));
    out->push_back(region_in(a, u_lo, u_hi, std::min(a_v[k], b_v[k]), std::max(a_v[k], b_v[k]), n0, n1));
  }
}

// This thread's rays logged to `to` while it lives.
struct LoggedTo {
  explicit LoggedTo(std::vector<RaySegment>* to) { thread_ray_log() = to; }
  ~LoggedTo() { thread_ray_log() = nullptr; }
  LoggedTo(const LoggedTo&) = delete;
  LoggedTo& operator=(const LoggedTo&) = delete;
};

bool path_meets(const std::vector<RaySegment>& segments, uint32_t first, uint32_t last,
                const std::vector<ChangedRegion>& regions) {
  for (uint32_t s = first; s < last; ++s)
    for (const ChangedRegion& r : regions)
      if (r.met_by(segments[s])) return true;
  return false;
}

}  // namespace

static_assert(sizeof(RaySegment) == 32, "docs/cost.md and the cost model count 32 bytes a kept ray");

bool ChangedRegion::met_by(const RaySegment& s) const {
  const Vec3 o = s.org - origin;
  const float org[3] = {o.dot(u_axis), o.dot(v_axis), o.dot(normal)};
  const float dir[3] = {s.dir.dot(u_axis), s.dir.dot(v_axis), s.dir.dot(normal)};
  float t0 = s.t0, t1 = s.t1;
  for (int k = 0; k < 3; ++k) {
    if (dir[k] == 0.0f) {
      if (org[k] < lo[k] || org[k] > hi[k]) return false;
      continue;
    }
    float a = (lo[k] - org[k]) / dir[k], b = (hi[k] - org[k]) / dir[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

std::optional<std::vector<ChangedRegion>> changed_regions(const CutterSet& before, const CutterSet& after) {
  std::vector<ChangedRegion> out;
  const size_t n = std::max(before.size(), after.size());
  for (size_t i = 0; i < n; ++i) {
    const Cutter* a = i < before.size() ? &before[i] : nullptr;
    const Cutter* b = i < after.size() ? &after[i] : nullptr;
    if (a && b && same_cutter(*a, *b)) continue;
    if ((a && a->chart) || (b && b->chart)) return std::nullopt;
    if (a && b && same_frame(*a, *b)) {
      add_moved_sides(*a, *b, &out);
      continue;
    }
    if (a) out.push_back(whole(*a));
    if (b) out.push_back(whole(*b));
  }
  return out;
}

SensorValues KeptCut::cut(const Scene& scene, const std::vector<OpeningInput>& openings,
                          const std::vector<size_t>& sensors, Progress* progress, int paths, uint64_t stream) {
  for (size_t s : sensors)
    if (s >= scene.sensors.size())
      throw std::invalid_argument("sensor " + std::to_string(s) + " is not one of the scene's " +
                                  std::to_string(scene.sensors.size()));
  OpeningsGeometry g = build_openings(scene, openings);
  auto cutters = std::make_shared<const CutterSet>(g.cutters);
  const PathTracer tracer(scene, std::move(g.cutters), std::move(g.reveals));
  for (size_t s : sensors) tracer.check_sensors({s, s + 1});
  paths = paths > 0 ? paths : scene.render.paths_per_sensor;
  const uint64_t seed = cut_seed(scene, stream);
  const size_t tasks_per_sensor = path_tasks_per_sensor(paths);

  // Per sensor of the list: its kept paths and the regions they must keep out of, or nothing kept.
  std::vector<const SensorPaths*> kept(sensors.size(), nullptr);
  std::vector<std::vector<ChangedRegion>> regions(sensors.size());
  for (size_t i = 0; i < sensors.size(); ++i) {
    const auto found = sensors_.find(sensors[i]);
    if (found == sensors_.end() || found->second.scene != &scene || found->second.paths != paths ||
        found->second.seed != seed)
      continue;
    std::optional<std::vector<ChangedRegion>> changed = changed_regions(*found->second.cutters, *cutters);
    if (!changed) continue;
    kept[i] = &found->second;
    regions[i] = std::move(*changed);
  }

  std::vector<ReplicateSums> sums(sensors.size() * tasks_per_sensor);
  std::vector<TaskPaths> traced(sums.size());
  std::vector<uint64_t> traced_paths(sums.size(), 0);
  if (progress) progress->start("tracing the scene with its openings", sums.size());
  parallel_path_tasks(sensors, paths, scene.render.threads, progress, [&](const PathTask& task) {
    const size_t i = task.index / tasks_per_sensor, t = task.index % tasks_per_sensor;
    const TaskPaths* before = kept[i] ? &kept[i]->tasks[t] : nullptr;
    TaskPaths& now = traced[task.index];
    for (size_t p = task.first; p < task.last; ++p) {
      const size_t k = p - task.first;
      const uint32_t first = k == 0 || !before ? 0 : before->end[k - 1];
      float value;
      if (before && !path_meets(before->segments, first, before->end[k], regions[i])) {
        value = before->value[k];
        now.segments.insert(now.segments.end(), before->segments.begin() + first, before->segments.begin() + before->end[k]);
      } else {
        Rng rng = path_rng(seed, task.sensor, p);
        const std::optional<PathSamples> samples = path_samples(scene.render, seed, task.sensor, p);
        const LoggedTo logged(&now.segments);
        value = tracer.sensor_sample(task.sensor, samples ? &*samples : nullptr, rng);
        ++traced_paths[task.index];
      }
      sums[task.index].add(p, value);
      now.value.push_back(value);
      now.end.push_back(static_cast<uint32_t>(now.segments.size()));
    }
  });

  for (size_t i = 0; i < sensors.size(); ++i) {
    SensorPaths& keep = sensors_[sensors[i]];
    keep.tasks.assign(std::make_move_iterator(traced.begin() + static_cast<std::ptrdiff_t>(i * tasks_per_sensor)),
                      std::make_move_iterator(traced.begin() + static_cast<std::ptrdiff_t>((i + 1) * tasks_per_sensor)));
    keep.scene = &scene;
    keep.paths = paths;
    keep.seed = seed;
    keep.cutters = cutters;
  }
  for (uint64_t n : traced_paths) traced_ += n;
  reused_ += static_cast<uint64_t>(sensors.size()) * static_cast<uint64_t>(paths);
  for (uint64_t n : traced_paths) reused_ -= n;
  return cut_values(sums, sensors.size(), paths);
}

size_t KeptCut::bytes() const {
  size_t out = 0;
  for (const auto& [sensor, kept] : sensors_)
    for (const TaskPaths& t : kept.tasks)
      out += t.value.capacity() * sizeof(float) + t.end.capacity() * sizeof(uint32_t) +
             t.segments.capacity() * sizeof(RaySegment);
  return out;
}

}  // namespace fenestra
