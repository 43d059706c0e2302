// Models in site coordinates (UTM eastings and northings): read in double, traced in a local frame,
// reported back where they were given. The same room anywhere on Earth gives the same numbers.
#include <gtest/gtest.h>

#include <cstdio>
#include <iomanip>

#include "annual/annual_contributions.h"
#include "io/results.h"
#include "scene/scene.h"
#include "scene/site_frame.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::TempDir;

TEST(SiteFrame, ModelsNearTheOriginAreTracedAsGiven) {
  EXPECT_FALSE(SiteFrame::around(Vec3d(-3, 0, 0), Vec3d(100, 128, 2.5)).shifted());
  const SiteFrame far = SiteFrame::around(Vec3d(499990.2, 9999990.0, 10.0), Vec3d(500003.0, 9999993.0, 12.5));
  EXPECT_EQ(far.origin, Vec3d(499997, 9999992, 11));  // the centre in whole meters
  EXPECT_EQ(SiteFrame::around(Vec3d(-201, 0, 0), Vec3d(200, 1, 1)).origin.x(), 0.0);  // -0.5 rounds up
  EXPECT_EQ(SiteFrame::around(Vec3d(999799, 0, 0), Vec3d(1000200, 1, 1)).origin.x(), 1000000.0);
}

TEST(SiteFrame, PositionsRoundTripExactly) {
  const SiteFrame frame = SiteFrame::around(Vec3d(9e6, 9e6, 9e6), Vec3d(9e6 + 4, 9e6 + 3, 9e6 + 2.5));
  for (const Vec3d p : {Vec3d(9e6 + 0.25, 9e6 + 2.75, 9e6 + 1.125), Vec3d(9e6, 9e6 + 3, 9e6 + 2.5)}) {
    EXPECT_EQ(frame.to_site(frame.to_local(p)), p);
  }
  // A float near 9e6 m keeps 1 m; the local frame keeps a micrometre.
  const Vec3d p(9e6 + 1.2345678, 9e6 + 0.5, 9e6 + 2.0);
  EXPECT_NEAR((frame.to_site(frame.to_local(p)) - p).norm(), 0.0, 1e-6);
}

// A 3 x 3 x 2.5 m room at `offset` whose south wall is the opening domain (0.5 m elements), three
// sensors, a uniform sky. Written with 17 digits: the offsets are the whole point.
Scene room_at(const TempDir& dir, const Vec3d& offset, int paths) {
  std::ostringstream obj;
  obj << std::setprecision(17);
  const double x0 = offset.x(), y0 = offset.y(), z0 = offset.z(), x1 = x0 + 3, y1 = y0 + 3, z1 = z0 + 2.5;
  const std::vector<std::pair<std::string, std::vector<Vec3d>>> faces = {
      {"floor", {{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}}},
      {"ceiling", {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}},
      {"south", {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}},
      {"north", {{x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}}},
      {"west", {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}},
      {"east", {{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}}};
  int n = 0;
  for (const auto& [name, quad] : faces) {
    obj << "o " << name << "\nusemtl " << (name == "south" ? "facade" : "grey") << "\n";
    for (const Vec3d& p : quad) obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    obj << "f " << n + 1 << " " << n + 2 << " " << n + 3 << " " << n + 4 << "\n";
    n += 4;
  }
  dir.write("scene.obj", obj.str());
  std::ostringstream json;
  json << std::setprecision(17) << R"({"fenestra": 1, "geometry": "scene.obj",
    "materials": {"grey": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}},
    "opening_domain": {"materials": ["facade"], "element_size": 0.5}, "sensors": {"points": [)";
  const Vec3d sensors[] = {{1.5, 1.0, 0.8}, {0.5, 2.5, 0.8}, {2.5, 0.5, 1.2}};
  for (int i = 0; i < 3; ++i) {
    const Vec3d p = sensors[i] + offset;
    json << (i ? ", " : "") << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  }
  json << R"(], "normals": [0, 0, 1]}, "sky": {"type": "uniform", "radiance": 318.3},
    "render": {"paths_per_sensor": )"
       << paths << R"(, "seed": 7}})";
  dir.write("scene.json", json.str());
  return load_scene(dir.file("scene.json"));
}

// A window of the south wall, in the room's own coordinates (meters from its lower south-west corner).
std::string window_at(const Vec3d& offset) {
  std::ostringstream s;
  s << std::setprecision(17) << R"({"openings": [{"corners": [)";
  const Vec3d corners[] = {{0.5, 0, 0.5}, {2.5, 0, 0.5}, {2.5, 0, 2.0}, {0.5, 0, 2.0}};
  for (int c = 0; c < 4; ++c) {
    const Vec3d p = corners[c] + offset;
    s << (c ? ", " : "") << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  }
  s << "]}]}";
  return s.str();
}

struct RoomRun {
  Contributions c;
  SensorValues window;
  std::vector<Element> elements;
  SiteFrame site;
};

RoomRun run_room_at(const Vec3d& offset) {
  TempDir dir;
  const Scene scene = room_at(dir, offset, 4096);
  dir.write("openings.json", window_at(offset));
  RoomRun run{compute_contributions(scene),
              evaluate_openings(scene, read_openings(dir.file("openings.json"), scene.site)),
              scene.domain.elements(), scene.site};
  return run;
}

TEST(SiteFrame, TheSameRoomGivesTheSameNumbersAnywhereOnTheSite) {
  const RoomRun home = run_room_at(Vec3d::Zero());
  EXPECT_FALSE(home.site.shifted());
  for (int axis = 0; axis < 3; ++axis) {
    const RoomRun* first_far = nullptr;
    std::vector<RoomRun> runs;
    runs.reserve(3);
    for (double distance : {1e5, 1e6, 9e6}) {
      Vec3d offset = Vec3d::Zero();
      offset[axis] = distance;
      runs.push_back(run_room_at(offset));
      const RoomRun& far = runs.back();
      const std::string where = "offset " + std::to_string(distance) + " m along axis " + std::to_string(axis);
      EXPECT_TRUE(far.site.shifted()) << where;
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(far.c.closed.value[i], 0.0) << where << ": the closed room leaks, sensor " << i;
        EXPECT_TRUE(test::within_sigma(far.c.all_open.value[i], far.c.all_open.standard_error[i],
                                       home.c.all_open.value[i], home.c.all_open.standard_error[i]))
            << where << ", all open, sensor " << i;
        EXPECT_TRUE(test::within_sigma(far.window.value[i], far.window.standard_error[i], home.window.value[i],
                                       home.window.standard_error[i]))
            << where << ", the window cut, sensor " << i;
      }
      // Elements come back where they lie on the site.
      ASSERT_EQ(far.elements.size(), home.elements.size());
      for (size_t k = 0; k < far.elements.size(); ++k)
        for (int c = 0; c < 4; ++c)
          EXPECT_LT((far.site.to_site(far.elements[k].corners[c]) - offset -
                     home.site.to_site(home.elements[k].corners[c])).norm(), 1e-6)
              << where << ", element " << k;
      // Away from the origin the local frame is the same whatever the distance: so are the numbers.
      if (!first_far) {
        first_far = &runs.front();
        continue;
      }
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(far.c.all_open.value[i], first_far->c.all_open.value[i]) << where;
        EXPECT_EQ(far.window.value[i], first_far->window.value[i]) << where;
        for (size_t k = 0; k < far.elements.size(); ++k) EXPECT_EQ(far.c.E(i, k), first_far->c.E(i, k)) << where;
      }
    }
  }
}

TEST(SiteFrame, CoordinatesBeyondUtmAndScenesWiderThanTheLocalRangeAreRefused) {
  TempDir dir;
  EXPECT_NO_THROW(room_at(dir, Vec3d(0, 9999996, 0), 16));  // a northing of 1e7 m less the room
  try {
    room_at(dir, Vec3d(0, 1.1e7, 0), 16);
    ADD_FAILURE() << "a northing of 1.1e7 m was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1e+07 m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fenestra
