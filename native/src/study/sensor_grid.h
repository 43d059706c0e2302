#pragma once
// Sensor grids where a person means them: over the upper face of each room's floor, at a height
// above that face, kept off the walls, one group per room. The Blender add-on's Add Sensor Grid
// and fenestra.sensor_grid() build grids with this; docs/sensors.md says how it reads a model.
//
// A model is read along vertical columns (one ray down through everything). A floor is a face of
// the chosen objects, within 45 degrees of horizontal, with room above it for the sensors. Where a
// room's floor looks up and its ceiling down (a room inside a solid), the space between a face
// looking down and one looking up above it is solid (a thick wall's inside); else rooms are thin
// boxes, whose normals may point out of them. With any floor under a ceiling in the model, floors
// open to the sky (a roof's top) are left out. Neighbouring columns
// are in one room where their floors are within kFloorStep and nothing stands between them at the
// sensors' height nor just under the ceiling (a door joins no rooms; its head separates them).
#include <array>
#include <cstdint>
#include <vector>

#include "scene/site_frame.h"

namespace fenestra {

struct SensorGridSettings {
  double height = 0.8;   // meters above the floor's upper face
  double spacing = 0.5;  // meters between neighbouring sensors, in x and y
  double inset = -1.0;   // meters kept off the walls; negative: automatic_inset(spacing)
};

// Half the spacing, at least 0.25 m: sDA and EN 17037 practice keeps sensors off the walls.
double automatic_inset(double spacing);

inline constexpr double kFloorStep = 0.35;          // meters: floors this close in height are one floor
inline constexpr double kGridClearance = 0.05;      // meters: sensors keep this off every face but their floor
inline constexpr double kMaxGridSensors = 1000000;  // a grid above this is refused before it is made

struct SensorRoom {
  std::vector<Vec3d> points;               // meters, in the input's coordinates; normals are +z
  std::vector<double> floor_z;             // the floor's upper face under each point (meters)
  std::vector<std::array<int, 4>> quads;   // neighbouring points, for painting goals over the grid
};

struct SensorGrid {
  std::vector<SensorRoom> rooms;  // by floor height, then x, then y
  double inset = 0.0;             // meters, as used
  bool enclosed = false;          // the floors are under ceilings (else the model's open floors)
};

// `positions` (meters, any coordinates: site coordinates are read in a local frame) and
// `triangles` are every face that can bound a room; `floor_candidates[t]` marks the faces of the
// objects chosen to hold sensors. Throws std::invalid_argument on bad settings or a grid above
// kMaxGridSensors; returns no rooms when no floor is found.
SensorGrid sensor_grid(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles,
                       const std::vector<uint8_t>& floor_candidates, const SensorGridSettings& settings);

}  // namespace fenestra
