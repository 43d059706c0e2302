#pragma once
// Ground truth: the scene path-traced with the given openings really cut, independent of E.
#include <array>
#include <vector>

#include "scene/scene.h"
#include "trace/contributions.h"
#include "util/progress.h"

namespace fenestra {

using Rectangle = std::array<Vec3, 4>;  // corners in order, world coordinates (meters)

struct OpeningsGeometry {
  CutterSet cutters;
  Mesh reveals;  // faces lining the cuts through a wall of non-zero thickness
};

// Validates the rectangles against the opening domain (throws std::invalid_argument naming the
// opening) and builds their cutters and reveal faces.
OpeningsGeometry build_openings(const Scene& scene, const std::vector<Rectangle>& openings);

SensorValues evaluate_openings(const Scene& scene, const std::vector<Rectangle>& openings,
                               Progress* progress = nullptr);

}  // namespace fenestra
