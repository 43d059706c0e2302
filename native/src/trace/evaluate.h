#pragma once
// Ground truth: the scene path-traced with the given openings really cut, independent of E.
#include <array>
#include <optional>
#include <vector>

#include "scene/scene.h"
#include "trace/contributions.h"
#include "trace/open_region.h"
#include "util/progress.h"
#include "trace/sensor_range.h"

namespace fenestra {

using Rectangle = std::array<Vec3, 4>;  // corners in order, world coordinates (meters)

// An opening as scene files and results give it: a rectangle of a panel's parameter domain (any
// panel, the only form on curved ones), or else four world corners in order around it (on a flat
// panel).
struct OpeningInput {
  std::optional<PanelRectangle> parameter;
  Rectangle corners{};
  OpeningInput() = default;
  OpeningInput(const Rectangle& c) : corners(c) {}  // NOLINT: corners are the common form
  OpeningInput(const PanelRectangle& r) : parameter(r) {}  // NOLINT
};

// The opening as a rectangle of its panel; throws std::invalid_argument (without naming the
// opening) when it is no rectangle, lies on no panel, or leaves its panel's parameter domain.
PanelRectangle to_panel_rectangle(const OpeningDomain& domain, const OpeningInput& opening);

struct OpeningsGeometry {
  CutterSet cutters;
  Mesh reveals;  // faces lining the cuts through a wall of non-zero thickness
};

// Validates the rectangles against the opening domain (throws std::invalid_argument naming the
// opening) and builds their cutters and reveal faces.
OpeningsGeometry build_openings(const Scene& scene, const std::vector<OpeningInput>& openings);

// Paths per sensor: `paths_per_sensor`, or the scene's render.paths_per_sensor when 0.
// `sensors`: only that block of the scene's sensors (a shard), equal bit for bit to their values
// in the whole scene's run. `stream`: random numbers of their own (0: the scene's evaluation's), for
// cuts that choose openings, so that the check of the chosen ones is independent of the choice.
SensorValues evaluate_openings(const Scene& scene, const std::vector<OpeningInput>& openings,
                               Progress* progress = nullptr, int paths_per_sensor = 0, SensorRange sensors = {},
                               uint64_t stream = 0);
// The same at the listed sensors only (the scene's indices, in the order given): each sensor's
// values bit for bit those of a run over the whole scene. For cuts that change what only some
// sensors can see.
SensorValues evaluate_openings_at(const Scene& scene, const std::vector<OpeningInput>& openings,
                                  const std::vector<size_t>& sensors, Progress* progress = nullptr,
                                  int paths_per_sensor = 0, uint64_t stream = 0);

}  // namespace fenestra
