#pragma once
// A cut (the scene path-traced with openings really cut, trace/evaluate.h) whose paths are kept: each
// path's value and the parts of rays it looked along. The next cut of openings that differ from the
// kept ones only in small regions (a side moved by a few centimetres, one opening of several
// changed) traces again only the paths whose rays came within those regions. Every other path has
// the same random numbers, asks the same rays and meets the same surfaces (the geometry differs only
// inside the regions, and cutters decide a hit by where it lies), so its kept value is its value:
// the cut equals evaluate_openings_at's bit for bit, for a share of the rays. The searches with real
// cutters in thick walls cut openings one side apart, again and again. Assumed of Embree: a ray
// meets the same surface whatever else the tree holds. An opening's reveal on an element's grid line
// and the wall's tube face there coincide; met at exactly one distance, the tree's order picks one,
// of the same material (and normal, on walls along the axes: docs/solver.md, step 7).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "trace/ray_scene.h"
#include "util/progress.h"

namespace fenestra {

// A region where two sets of cutters may differ: a box in a cutter's frame (origin and axes), with
// its extent along u, v and the normal (meters).
struct ChangedRegion {
  Vec3 origin, u_axis, v_axis, normal;
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  // Whether org + t dir meets the box for some t in [t0, t1].
  bool met_by(const RaySegment& s) const;
};

// The regions outside which `before` and `after` cut the same solid and line it with the same reveal
// faces: for an opening moved within its panel's plane, a slab per side that moved (between its two
// positions, along the whole of both openings' other extent, through the cutter's depth) and a thin
// one about each side's plane that did not; for one
// added, removed or reshaped otherwise, its whole box. nullopt where no box holds the change (a cutter
// on a curved panel's chart).
std::optional<std::vector<ChangedRegion>> changed_regions(const CutterSet& before, const CutterSet& after);

class KeptCut {
 public:
  // evaluate_openings_at(scene, openings, sensors, progress, paths, stream), bit for bit; the paths
  // of `sensors` are kept (replacing what was kept of them). Paths kept from a cut of other `paths`
  // or `stream`, or of a scene whose cutters changed beyond any region, are traced again.
  SensorValues cut(const Scene& scene, const std::vector<OpeningInput>& openings, const std::vector<size_t>& sensors,
                   Progress* progress, int paths, uint64_t stream);

  size_t bytes() const;           // what the kept paths hold
  uint64_t paths_traced() const { return traced_; }    // over every cut so far
  uint64_t paths_reused() const { return reused_; }    // kept values taken instead of tracing

 private:
  // One task's paths (kPathsPerTask of them, in order): values, and where each path's segments end.
  struct TaskPaths {
    std::vector<float> value;
    std::vector<uint32_t> end;
    std::vector<RaySegment> segments;
  };
  struct SensorPaths {
    const Scene* scene = nullptr;  // the scene they were traced in (kept paths answer for no other)
    int paths = 0;
    uint64_t seed = 0;
    std::shared_ptr<const CutterSet> cutters;
    std::vector<TaskPaths> tasks;
  };
  std::map<size_t, SensorPaths> sensors_;
  uint64_t traced_ = 0, reused_ = 0;
};

}  // namespace fenestra
