// Sensor grids (study/sensor_grid.h): over a solid room's floor at the height above its upper face,
// off the walls, one group per room (a door's head parts rooms, storeys are rooms), the same in
// site coordinates, and bad settings refused before anything is made.
#include "study/sensor_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fenestra {
namespace {

struct Soup {
  std::vector<Vec3d> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint8_t> floors;  // faces that may hold sensors

  void quad(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, bool floor) {
    const uint32_t n = static_cast<uint32_t>(positions.size());
    positions.insert(positions.end(), {a, b, c, d});
    triangles.push_back({n, n + 1, n + 2});
    triangles.push_back({n, n + 2, n + 3});
    floors.insert(floors.end(), {uint8_t(floor), uint8_t(floor)});
  }
  // A box's six faces, facing out (or in: a room's cavity inside a solid).
  void box(const Vec3d& lo, const Vec3d& hi, bool inward, bool floor) {
    const Vec3d c[8] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()},
                        {lo.x(), hi.y(), lo.z()}, {lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()},
                        {hi.x(), hi.y(), hi.z()}, {lo.x(), hi.y(), hi.z()}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& f : faces)
      if (inward) quad(c[f[0]], c[f[3]], c[f[2]], c[f[1]], floor);
      else quad(c[f[0]], c[f[1]], c[f[2]], c[f[3]], floor);
  }
  void move(const Vec3d& by) {
    for (Vec3d& p : positions) p += by;
  }
};

// A room 4 x 5 x 3 m inside one solid: walls 0.3 m, slabs 0.2 m (the whole room selected).
Soup solid_room() {
  Soup s;
  s.box({-0.3, -0.3, -0.2}, {4.3, 5.3, 3.2}, false, true);
  s.box({0, 0, 0}, {4, 5, 3}, true, true);
  return s;
}

SensorGrid grid(const Soup& s, double height, double spacing, double inset = -1.0) {
  SensorGridSettings settings;
  settings.height = height, settings.spacing = spacing, settings.inset = inset;
  return sensor_grid(s.positions, s.triangles, s.floors, settings);
}

// Each point's distance to the nearest of the cavity's walls (x in [x0, x1], y in [y0, y1]).
double wall_distance(const Vec3d& p, double x0, double x1, double y0, double y1) {
  return std::min({p.x() - x0, x1 - p.x(), p.y() - y0, y1 - p.y()});
}

TEST(SensorGrid, ASolidRoomsGridLiesOverTheFloorsUpperFaceOffTheWalls) {
  const SensorGrid g = grid(solid_room(), 0.8, 0.5);
  ASSERT_EQ(g.rooms.size(), 1u);
  EXPECT_TRUE(g.enclosed);
  EXPECT_DOUBLE_EQ(g.inset, 0.25);
  const SensorRoom& room = g.rooms[0];
  ASSERT_EQ(room.points.size(), 80u);  // 8 x 10 at 0.5 m over 4 x 5 m, 0.25 m off the walls
  EXPECT_EQ(room.quads.size(), 7u * 9u);
  for (size_t i = 0; i < room.points.size(); ++i) {
    EXPECT_NEAR(room.floor_z[i], 0.0, 1e-5);                 // the slab's upper face, not its underside
    EXPECT_NEAR(room.points[i].z(), 0.8, 1e-5);
    EXPECT_GE(wall_distance(room.points[i], 0, 4, 0, 5), 0.25 - 1e-4) << room.points[i].transpose();
  }
  // Centred: the first and last rows as far from their walls.
  double lo = 1e9, hi = -1e9;
  for (const Vec3d& p : room.points) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
  EXPECT_NEAR(lo, 4.0 - hi, 1e-4);
}

// A closed thin box (Blender's cube scaled to a room: normals out, the floor's down) is a room, and
// inside a solid wall 0.8 m thick, next to a room inside a solid, is none.
TEST(SensorGrid, ThinBoxRoomsWithOutwardNormalsAndThickSolidWalls) {
  Soup box;
  box.box({0, 0, 0}, {4, 5, 3}, false, true);
  const SensorGrid thin = grid(box, 0.8, 0.5);
  ASSERT_EQ(thin.rooms.size(), 1u);
  EXPECT_EQ(thin.rooms[0].points.size(), 80u);
  EXPECT_NEAR(thin.rooms[0].floor_z[0], 0.0, 1e-5);
  Soup thick;
  thick.box({-0.8, -0.8, -0.2}, {4.8, 5.8, 3.2}, false, true);
  thick.box({0, 0, 0}, {4, 5, 3}, true, true);
  const SensorGrid g = grid(thick, 0.8, 0.5);
  ASSERT_EQ(g.rooms.size(), 1u);
  for (const Vec3d& p : g.rooms[0].points) EXPECT_GE(wall_distance(p, 0, 4, 0, 5), 0.25 - 1e-4) << p.transpose();
}

TEST(SensorGrid, TheInsetIsHalfTheSpacingAtLeastAQuarterMetreOrAsGiven) {
  EXPECT_DOUBLE_EQ(automatic_inset(0.3), 0.25);
  EXPECT_DOUBLE_EQ(automatic_inset(1.0), 0.5);
  const SensorGrid wide = grid(solid_room(), 0.85, 1.0);
  for (const Vec3d& p : wide.rooms.at(0).points) EXPECT_GE(wall_distance(p, 0, 4, 0, 5), 0.5 - 1e-4);
  const SensorGrid given = grid(solid_room(), 0.85, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(given.inset, 1.0);
  ASSERT_FALSE(given.rooms.empty());
  for (const Vec3d& p : given.rooms[0].points) EXPECT_GE(wall_distance(p, 0, 4, 0, 5), 1.0 - 1e-4);
}

TEST(SensorGrid, ModelsInSiteCoordinatesGetTheSameGrid) {
  const SensorGrid near = grid(solid_room(), 0.8, 0.5);
  for (const Vec3d& offset : {Vec3d(100, 0, 0), Vec3d(500000.0, 4600000.0, 212.0), Vec3d(683123.0, 9876543.0, 0)}) {
    Soup s = solid_room();
    s.move(offset);
    const SensorGrid far = grid(s, 0.8, 0.5);
    ASSERT_EQ(far.rooms.size(), 1u) << offset.transpose();
    ASSERT_EQ(far.rooms[0].points.size(), near.rooms[0].points.size()) << offset.transpose();
    for (size_t i = 0; i < far.rooms[0].points.size(); ++i)
      EXPECT_LT((far.rooms[0].points[i] - offset - near.rooms[0].points[i]).norm(), 1e-4) << offset.transpose();
  }
}

// Two thin-walled rooms joined by a door 1 x 2.1 m in the partition x = 2: the door's head parts them.
TEST(SensorGrid, ADoorJoinsNoRooms) {
  Soup s;
  s.quad({0, 0, 0}, {4, 0, 0}, {4, 5, 0}, {0, 5, 0}, true);
  s.quad({0, 0, 3}, {0, 5, 3}, {4, 5, 3}, {4, 0, 3}, false);
  s.quad({0, 0, 0}, {0, 0, 3}, {4, 0, 3}, {4, 0, 0}, false);
  s.quad({0, 5, 0}, {4, 5, 0}, {4, 5, 3}, {0, 5, 3}, false);
  s.quad({0, 0, 0}, {0, 5, 0}, {0, 5, 3}, {0, 0, 3}, false);
  s.quad({4, 0, 0}, {4, 0, 3}, {4, 5, 3}, {4, 5, 0}, false);
  s.quad({2, 0, 0}, {2, 2, 0}, {2, 2, 3}, {2, 0, 3}, false);
  s.quad({2, 3, 0}, {2, 5, 0}, {2, 5, 3}, {2, 3, 3}, false);
  s.quad({2, 2, 2.1}, {2, 3, 2.1}, {2, 3, 3}, {2, 2, 3}, false);
  const SensorGrid g = grid(s, 0.8, 0.5);
  ASSERT_EQ(g.rooms.size(), 2u);
  for (int r = 0; r < 2; ++r) {
    ASSERT_EQ(g.rooms[r].points.size(), 40u);
    for (const Vec3d& p : g.rooms[r].points)
      EXPECT_GE(wall_distance(p, r == 0 ? 0 : 2, r == 0 ? 2 : 4, 0, 5), 0.25 - 1e-4) << p.transpose();
  }
  EXPECT_LT(g.rooms[0].points[0].x(), 2.0);  // ordered by x
  EXPECT_GT(g.rooms[1].points[0].x(), 2.0);
}

TEST(SensorGrid, StoreysAreRoomsAndRoofsAreNot) {
  Soup s = solid_room();
  Soup upper;
  upper.box({-0.3, -0.3, 3.2}, {4.3, 5.3, 6.6}, false, true);
  upper.box({0, 0, 3.4}, {4, 5, 6.4}, true, true);
  const uint32_t n = static_cast<uint32_t>(s.positions.size());
  for (auto t : upper.triangles) s.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  s.positions.insert(s.positions.end(), upper.positions.begin(), upper.positions.end());
  s.floors.insert(s.floors.end(), upper.floors.begin(), upper.floors.end());
  const SensorGrid g = grid(s, 0.8, 0.5);
  ASSERT_EQ(g.rooms.size(), 2u);  // not the roof's top (open to the sky)
  EXPECT_NEAR(g.rooms[0].floor_z[0], 0.0, 1e-5);
  EXPECT_NEAR(g.rooms[1].floor_z[0], 3.4, 1e-5);
  EXPECT_NEAR(g.rooms[1].points[0].z(), 4.2, 1e-5);
}

TEST(SensorGrid, OnlyTheChosenFloorsHoldSensors) {
  Soup s = solid_room();
  Soup other;
  other.box({10 - 0.3, -0.3, -0.2}, {14.3, 5.3, 3.2}, false, false);
  other.box({10, 0, 0}, {14, 5, 3}, true, false);
  const uint32_t n = static_cast<uint32_t>(s.positions.size());
  for (auto t : other.triangles) s.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  s.positions.insert(s.positions.end(), other.positions.begin(), other.positions.end());
  s.floors.insert(s.floors.end(), other.floors.begin(), other.floors.end());
  const SensorGrid g = grid(s, 0.8, 0.5);
  ASSERT_EQ(g.rooms.size(), 1u);
  for (const Vec3d& p : g.rooms[0].points) EXPECT_LT(p.x(), 4.0);
}

TEST(SensorGrid, AFloorAloneGetsAGridOverItKeptOffItsEdges) {
  Soup s;
  s.quad({0, 0, 0}, {4, 0, 0}, {4, 5, 0}, {0, 5, 0}, true);
  const SensorGrid g = grid(s, 0.8, 0.5);
  EXPECT_FALSE(g.enclosed);
  ASSERT_EQ(g.rooms.size(), 1u);
  EXPECT_EQ(g.rooms[0].points.size(), 80u);
  for (const Vec3d& p : g.rooms[0].points) EXPECT_GE(wall_distance(p, 0, 4, 0, 5), 0.25 - 1e-4);
  // Its normal facing down changes nothing: thin floors are read either way up.
  Soup flipped;
  flipped.quad({0, 0, 0}, {0, 5, 0}, {4, 5, 0}, {4, 0, 0}, true);
  EXPECT_EQ(grid(flipped, 0.8, 0.5).rooms.at(0).points.size(), 80u);
}

TEST(SensorGrid, ARoomTooLowForTheHeightGetsNoSensors) {
  EXPECT_TRUE(grid(solid_room(), 2.99, 0.5).rooms.empty());
  EXPECT_FALSE(grid(solid_room(), 2.9, 0.5).rooms.empty());
}

TEST(SensorGrid, BadSettingsAreRefusedBeforeAnythingIsMade) {
  const auto message = [](double height, double spacing, double inset) {
    try {
      grid(solid_room(), height, spacing, inset);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  EXPECT_NE(message(-1, 0.5, -1).find("height -1 m is not a length above 0 m"), std::string::npos);
  EXPECT_NE(message(0.8, 0, -1).find("spacing 0 m"), std::string::npos);
  EXPECT_NE(message(0.8, std::nan(""), -1).find("spacing nan m"), std::string::npos);
  EXPECT_NE(message(0.8, 0.5, std::nan("")).find("inset nan m"), std::string::npos);
  // 4.6 x 5.6 m at 1 mm: 26 million sensors; at the spacing suggested, the grid is made.
  const std::string big = message(0.8, 0.001, -1);
  EXPECT_NE(big.find("use a spacing of at least 0.01 m"), std::string::npos) << big;
  EXPECT_NO_THROW(grid(solid_room(), 0.8, 0.01));
}

}  // namespace
}  // namespace fenestra
