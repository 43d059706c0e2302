// Curved opening domains: charts (unrolled or from a UV map) and their refusals, and the exact
// evaluation from path records against `evaluate` with chart rectangles really cut.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "annual/annual_contributions.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using test::TempDir;
using test::within_sigma;

// OBJ text with faces given by corner positions (and optional UVs).
class ObjText {
 public:
  void object(const std::string& name, const std::string& material) { s_ << "o " << name << "\nusemtl " << material << "\n"; }
  void face(const std::vector<Vec3>& corners, const std::vector<Vec2>& uvs = {}) {
    for (const Vec3& p : corners) s_ << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Vec2& t : uvs) s_ << "vt " << t.x() << " " << t.y() << "\n";
    s_ << "f";
    for (size_t k = 0; k < corners.size(); ++k) {
      s_ << " " << vertices_ + k + 1;
      if (!uvs.empty()) s_ << "/" << texcoords_ + k + 1;
    }
    s_ << "\n";
    vertices_ += corners.size();
    texcoords_ += uvs.size();
  }
  std::string str() const { return s_.str(); }

 private:
  std::ostringstream s_;
  size_t vertices_ = 0, texcoords_ = 0;
};

Vec3 on_circle(float radius, float angle, float z) { return {radius * std::cos(angle), radius * std::sin(angle), z}; }

// `facets` vertical facets of a cylinder of `radius` about the z axis, from angle a0 to a1, 0 <= z <= h;
// with UVs u = angle fraction, v = z / h when `uv`.
void cylinder(ObjText* obj, float radius, float a0, float a1, int facets, float h, bool uv) {
  for (int i = 0; i < facets; ++i) {
    const float t0 = a0 + (a1 - a0) * i / facets, t1 = a0 + (a1 - a0) * (i + 1) / facets;
    const float u0 = static_cast<float>(i) / facets, u1 = static_cast<float>(i + 1) / facets;
    std::vector<Vec2> uvs;
    if (uv) uvs = {{u0, 0}, {u1, 0}, {u1, 1}, {u0, 1}};
    obj->face({on_circle(radius, t0, 0), on_circle(radius, t1, 0), on_circle(radius, t1, h), on_circle(radius, t0, h)}, uvs);
  }
}

Mesh mesh_of(const std::string& obj_text, const std::vector<std::string>& materials) {
  TempDir dir;
  dir.write("m.obj", obj_text);
  return load_obj(dir.file("m.obj"), materials);
}

std::vector<uint32_t> all_triangles(const Mesh& m) {
  std::vector<uint32_t> t(m.triangle_count());
  for (size_t i = 0; i < t.size(); ++i) t[i] = static_cast<uint32_t>(i);
  return t;
}

std::string chart_error(const std::string& obj_text) {
  const Mesh m = mesh_of(obj_text, {"facade"});
  try {
    SurfaceChart::build(m, all_triangles(m), "material 'facade'");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SurfaceChart, UnrollingKeepsLengthsAndLevels) {
  ObjText obj;
  obj.object("wall", "facade");
  const float r = 4.0f, h = 3.0f;
  cylinder(&obj, r, 0.0f, kPi / 2, 16, h, false);
  const Mesh m = mesh_of(obj.str(), {"facade"});
  const SurfaceChart chart = SurfaceChart::build(m, all_triangles(m), "wall");
  EXPECT_EQ(chart.source(), SurfaceChart::Source::kUnrolled);
  const float chord = 2.0f * r * std::sin(kPi / 64);
  EXPECT_NEAR(chart.upper().x() - chart.lower().x(), 16 * chord, 1e-4);
  EXPECT_NEAR(chart.upper().y() - chart.lower().y(), h, 1e-4);
  Rng rng(7, 0);
  for (int i = 0; i < 200; ++i) {
    const uint32_t t = static_cast<uint32_t>(rng.uniform() * m.triangle_count()) % m.triangle_count();
    float a = rng.uniform(), b = rng.uniform();
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    const Vec3 p = m.vertex(t, 0) + a * (m.vertex(t, 1) - m.vertex(t, 0)) + b * (m.vertex(t, 2) - m.vertex(t, 0));
    const Vec2 q = chart.chart_point(t, p);
    // Heights are kept: v runs up the wall.
    EXPECT_NEAR(q.y() - chart.lower().y(), p.z(), 1e-4);
    const SurfaceChart::SurfacePoint back = chart.surface_point(q);
    EXPECT_TRUE(back.on_surface);
    EXPECT_LT((back.position - p).norm(), 1e-4f);
    EXPECT_NEAR(back.area_ratio, 1.0f, 1e-4);
    // Along the wall, chart distance from the start is the arc length over the facets.
    const float angle = std::atan2(p.y(), p.x());
    const int facet = std::min(15, static_cast<int>(angle / (kPi / 32)));
    const float along = facet * chord + (p - on_circle(r, facet * kPi / 32, p.z())).norm();
    EXPECT_NEAR(std::abs(q.x() - (chart.upper().x() + chart.lower().x()) / 2),
                std::abs(along - 8 * chord), 2e-4);
  }
}

TEST(SurfaceChart, UvMapIsScaledToTheSurfacesArea) {
  ObjText obj;
  obj.object("wall", "facade");
  cylinder(&obj, 4.0f, 0.0f, kPi / 2, 16, 3.0f, true);
  const Mesh m = mesh_of(obj.str(), {"facade"});
  const SurfaceChart chart = SurfaceChart::build(m, all_triangles(m), "wall");
  EXPECT_EQ(chart.source(), SurfaceChart::Source::kUvMap);
  const float surface = 16 * 2.0f * 4.0f * std::sin(kPi / 64) * 3.0f;
  const Vec2 size = chart.upper() - chart.lower();
  EXPECT_NEAR(size.x() * size.y(), surface, 1e-3 * surface);
  EXPECT_NEAR(size.x(), size.y(), 1e-4);  // the UV square stays a square
  for (uint32_t t = 0; t < m.triangle_count(); ++t) EXPECT_NEAR(chart.area_ratio(t), 1.0f, 1e-3);
}

TEST(SurfaceChart, RefusesWhatCannotBeLaidFlat) {
  {  // a dome cap: not developable
    ObjText obj;
    obj.object("dome", "facade");
    const int n = 8;
    for (int ring = 0; ring < 3; ++ring)
      for (int i = 0; i < n; ++i) {
        const float a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
        const float e0 = 0.2f + 0.3f * ring, e1 = e0 + 0.3f;
        auto p = [](float az, float el) { return Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)); };
        obj.face({p(a0, e0), p(a1, e0), p(a1, e1), p(a0, e1)});
      }
    const std::string m = chart_error(obj.str());
    EXPECT_NE(m.find("cannot be unrolled"), std::string::npos) << m;
    EXPECT_NE(m.find("UV map"), std::string::npos) << m;
  }
  {  // a whole cylinder closes on itself
    ObjText obj;
    obj.object("tower", "facade");
    cylinder(&obj, 2.0f, 0.0f, 2 * kPi, 24, 3.0f, false);
    EXPECT_NE(chart_error(obj.str()).find("cannot be unrolled"), std::string::npos);
  }
  auto uv_wall = [](const std::vector<std::vector<Vec2>>& uvs) {
    ObjText obj;
    obj.object("wall", "facade");
    for (int i = 0; i < 4; ++i) {
      const float t0 = i * kPi / 16, t1 = (i + 1) * kPi / 16;
      obj.face({on_circle(4, t0, 0), on_circle(4, t1, 0), on_circle(4, t1, 3), on_circle(4, t0, 3)}, uvs[i]);
    }
    return obj.str();
  };
  auto quad_uv = [](float u0, float u1) { return std::vector<Vec2>{{u0, 0}, {u1, 0}, {u1, 1}, {u0, 1}}; };
  {  // degenerate: a facet's UVs on one line
    const std::string m = chart_error(uv_wall({quad_uv(0, 0.25f), quad_uv(0.25f, 0.5f), {{0.5f, 0}, {0.75f, 0}, {0.75f, 0}, {0.5f, 0}}, quad_uv(0.75f, 1)}));
    EXPECT_NE(m.find("degenerate"), std::string::npos) << m;
    EXPECT_NE(m.find("face at ("), std::string::npos) << m;
  }
  {  // folded: a facet mirrored in the map
    const std::string m = chart_error(uv_wall({quad_uv(0, 0.25f), quad_uv(0.25f, 0.5f), quad_uv(0.75f, 0.5f), quad_uv(0.75f, 1)}));
    EXPECT_NE(m.find("folds over"), std::string::npos) << m;
  }
  {  // overlapping: two facets on the same UVs (not neighbours, so no seam check catches it)
    const std::string m = chart_error(uv_wall({quad_uv(0, 0.25f), quad_uv(0.25f, 0.5f), quad_uv(0.5f, 0.75f), quad_uv(0, 0.25f)}));
    EXPECT_NE(m.find("overlaps itself"), std::string::npos) << m;
  }
}

// A quarter-circle room (radius 3 m, 2.5 m high): straight walls along +X and +Y, and 90 degrees of
// a cylinder (16 facets, the domain) between them; or, with `vault`, a 3 x 3 m room under a
// barrel vault of radius 1.5 m along X (16 facets, the domain).
struct Curved {
  bool vault;
  bool sun;
  bool uv;  // the domain carries a UV map (else it is unrolled)
};

std::string describe(const Curved& c) {
  return std::string(c.vault ? "vault" : "curved wall") + (c.uv ? ", UV map" : ", unrolled") + (c.sun ? ", sun" : ", overcast");
}

std::string curved_room_obj(const Curved& c, float thickness_behind = 0.0f) {
  ObjText obj;
  const int n = 16;
  if (!c.vault) {
    const float r = 3.0f, h = 2.5f;
    obj.object("floor", "plaster");
    for (int i = 0; i < n; ++i)
      obj.face({Vec3(0, 0, 0), on_circle(r, kPi / 2 * i / n, 0), on_circle(r, kPi / 2 * (i + 1) / n, 0)});
    obj.object("ceiling", "plaster");
    for (int i = 0; i < n; ++i)
      obj.face({Vec3(0, 0, h), on_circle(r, kPi / 2 * (i + 1) / n, h), on_circle(r, kPi / 2 * i / n, h)});
    obj.object("walls", "plaster");
    obj.face({Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(r, 0, h), Vec3(r, 0, 0)});
    obj.face({Vec3(0, 0, 0), Vec3(0, r, 0), Vec3(0, r, h), Vec3(0, 0, h)});
    obj.object("curved", "facade");
    cylinder(&obj, r, 0.0f, kPi / 2, n, h, c.uv);
    if (thickness_behind > 0.0f) {
      obj.object("curved_outer", "plaster");
      cylinder(&obj, r + thickness_behind, 0.0f, kPi / 2, n, h, false);
    }
  } else {
    const float w = 3.0f, d = 3.0f, h = 2.0f, r = 1.5f;
    auto arch = [&](int i) { const float t = kPi * i / n; return Vec2(d / 2 + r * std::cos(t), h + r * std::sin(t)); };
    obj.object("room", "plaster");
    obj.face({Vec3(0, 0, 0), Vec3(0, d, 0), Vec3(w, d, 0), Vec3(w, 0, 0)});
    obj.face({Vec3(0, 0, 0), Vec3(w, 0, 0), Vec3(w, 0, h), Vec3(0, 0, h)});
    obj.face({Vec3(0, d, 0), Vec3(0, d, h), Vec3(w, d, h), Vec3(w, d, 0)});
    obj.face({Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(0, d, h), Vec3(0, d, 0)});
    obj.face({Vec3(w, 0, 0), Vec3(w, d, 0), Vec3(w, d, h), Vec3(w, 0, h)});
    for (int i = 0; i < n; ++i) {  // gables
      obj.face({Vec3(0, d / 2, h), Vec3(0, arch(i).x(), arch(i).y()), Vec3(0, arch(i + 1).x(), arch(i + 1).y())});
      obj.face({Vec3(w, d / 2, h), Vec3(w, arch(i + 1).x(), arch(i + 1).y()), Vec3(w, arch(i).x(), arch(i).y())});
    }
    obj.object("vault", "facade");
    for (int i = 0; i < n; ++i) {
      const Vec2 a = arch(i), b = arch(i + 1);
      std::vector<Vec2> uvs;
      // Unevenly spaced around the arch: surface area per chart area differs from facet to facet.
      auto v = [&](int k) { return std::pow(static_cast<float>(k) / n, 1.5f); };
      if (c.uv) uvs = {{0, v(i)}, {0, v(i + 1)}, {1, v(i + 1)}, {1, v(i)}};
      obj.face({Vec3(0, a.x(), a.y()), Vec3(0, b.x(), b.y()), Vec3(w, b.x(), b.y()), Vec3(w, a.x(), a.y())}, uvs);
    }
  }
  obj.object("ground", "ground");
  obj.face({Vec3(-20, -20, -0.01f), Vec3(20, -20, -0.01f), Vec3(20, 20, -0.01f), Vec3(-20, 20, -0.01f)});
  return obj.str();
}

Scene curved_room(const TempDir& dir, const Curved& c, int paths, const std::string& extra_domain = "") {
  dir.write("scene.obj", curved_room_obj(c));
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"plaster": {"reflectance": 0.6}, "facade": {"reflectance": 0.5}, "ground": {"reflectance": 0.2}},
      "opening_domain": {"materials": ["facade"], "element_size": 0.3)"
    << extra_domain << R"(},
      "sensors": {"points": )"
    << (c.vault ? "[[1.5, 1.5, 0.8], [0.6, 0.6, 0.8], [2.4, 2.2, 0.8], [1.5, 0.8, 1.6]]"
                : "[[1, 1, 0.8], [0.5, 2, 0.8], [2, 0.5, 0.8], [1.2, 1.2, 1.6]]")
    << R"(, "normals": [0, 0, 1]},
      "sky": )"
    << (c.sun ? R"({"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2026-03-21",
                  "time": "10:00", "resolution": [128, 64]})"
              : R"({"type": "cie_overcast", "resolution": [128, 64]})")
    << R"(, "render": {"paths_per_sensor": )" << paths << R"(, "max_bounces": 6, "seed": 5}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

TEST(CurvedDomain, OnePanelDicedOverTheWholeSurface) {
  for (bool vault : {false, true}) {
    TempDir dir;
    const Scene scene = curved_room(dir, {vault, false, false}, 16);
    ASSERT_EQ(scene.domain.panels().size(), 1u) << (vault ? "vault" : "wall");
    const Panel& panel = scene.domain.panels()[0];
    EXPECT_TRUE(panel.curved());
    // Faceted: 16 chords of the arc; the grid covers all of it but the margins of the last element.
    const float radius = vault ? 1.5f : 3.0f, angle = vault ? kPi : kPi / 2, along = vault ? 3.0f : 2.5f;
    const float arc = 16 * 2 * radius * std::sin(angle / 32);
    const float a = scene.domain.element_size();
    const size_t expected = static_cast<size_t>(std::floor(arc / a + 1e-4f)) * static_cast<size_t>(std::floor(along / a + 1e-4f));
    EXPECT_EQ(scene.domain.element_count(), expected);
    EXPECT_GT(scene.domain.element_count() * a * a, 0.8 * panel.area);
    // Element corners on the surface: at the radius from the axis.
    for (const Element& e : scene.domain.elements())
      for (const Vec3& p : e.corners) {
        const float rr = vault ? std::hypot(p.y() - 1.5f, p.z() - 2.0f) : std::hypot(p.x(), p.y());
        EXPECT_LE(rr, radius + 1e-4f);
        EXPECT_GE(rr, radius * std::cos(angle / 32) - 1e-4f);
      }
    // Outward points away from the room: out of the cylinder.
    const DomainSurfacePoint s = scene.domain.surface_at(0, panel.cols * a / 2, panel.rows * a / 2);
    const Vec3 radial = vault ? Vec3(0, s.position.y() - 1.5f, s.position.z() - 2.0f) : Vec3(s.position.x(), s.position.y(), 0);
    EXPECT_GT(s.outward.dot(radial.normalized()), 0.99f);
  }
}

// The panel rectangle of the elements in rows r0..r1, columns c0..c1.
PanelRectangle cells(const Scene& scene, int r0, int r1, int c0, int c1) {
  const double a = scene.domain.element_size();
  return {0, c0 * a, (c1 + 1) * a, r0 * a, (r1 + 1) * a};
}

class CurvedRecords : public ::testing::TestWithParam<Curved> {};

TEST_P(CurvedRecords, ExactRecordsEqualEvaluateWithRealCuts) {
  const Curved cfg = GetParam();
  TempDir dir;
  const Scene scene = curved_room(dir, cfg, 1 << 13);
  const Contributions c = compute_contributions(scene);
  const Panel& panel = scene.domain.panels()[0];
  const double a = scene.domain.element_size();
  // A window across several facets, a ragged set of single elements, and a rectangle whose edges
  // lie between grid lines (the edge search's evaluation).
  std::vector<std::vector<PanelRectangle>> sets;
  sets.push_back({cells(scene, 2, 5, 2, 7)});
  {
    std::vector<PanelRectangle> ragged;
    for (int r = 1; r < panel.rows - 1; ++r)
      for (int col = 1; col < panel.cols - 1; ++col)
        if ((r * 5 + col * 3) % 4 == 0) ragged.push_back(cells(scene, r, r, col, col));
    sets.push_back(ragged);
  }
  sets.push_back({{0, 1.37 * a, 6.61 * a, 0.52 * a, 4.18 * a}});
  double max_z = 0.0;
  for (size_t set = 0; set < sets.size(); ++set) {
    const SensorValues exact = c.evaluate(OpenRegion(scene.domain, sets[set]));
    std::vector<OpeningInput> cuts(sets[set].begin(), sets[set].end());
    const SensorValues truth = evaluate_openings(scene, cuts);
    for (size_t i = 0; i < scene.sensors.size(); ++i) {
      EXPECT_GT(truth.value[i], 0.0);
      max_z = std::max(max_z, std::abs(exact.value[i] - truth.value[i]) /
                                  std::hypot(exact.standard_error[i], truth.standard_error[i]));
      EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
          << describe(cfg) << ", set " << set << ", sensor " << i;
    }
  }
  std::printf("[ curved   ] %s: records against real cuts, max |z| %.2f over %zu values\n", describe(cfg).c_str(),
              max_z, sets.size() * scene.sensors.size());
}

INSTANTIATE_TEST_SUITE_P(Surfaces, CurvedRecords,
                         ::testing::Values(Curved{false, false, false}, Curved{false, true, false},
                                           Curved{true, true, false}, Curved{true, false, true}));

TEST(CurvedDomain, CutsFollowTheSurface) {
  // The test above can tell: a window on the curved wall lets in light, many standard errors
  // above none, and its light differs from that of a window as wide elsewhere on the arc.
  TempDir dir;
  const Scene scene = curved_room(dir, {false, false, false}, 1 << 12);
  const SensorValues closed = evaluate_openings(scene, {});
  const SensorValues left = evaluate_openings(scene, {OpeningInput(cells(scene, 2, 5, 1, 4))});
  const SensorValues right = evaluate_openings(scene, {OpeningInput(cells(scene, 2, 5, 10, 13))});
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_GT(left.value[i] - closed.value[i], 8 * std::hypot(left.standard_error[i], closed.standard_error[i]));
  }
  // Sensor 2 (2, 0.5) is near the +X end of the arc (column 0), sensor 1 (0.5, 2) near the +Y end.
  EXPECT_GT(left.value[2] - right.value[2], 4 * std::hypot(left.standard_error[2], right.standard_error[2]));
  EXPECT_GT(right.value[1] - left.value[1], 4 * std::hypot(left.standard_error[1], right.standard_error[1]));
}

TEST(CurvedDomain, RefusesThicknessAndSolidsAndRectanglesOffThePanel) {
  TempDir dir;
  try {
    curved_room(dir, {false, false, false}, 16, R"(, "thickness": 0.3)");
    FAIL() << "a thickness on a curved panel was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("curved"), std::string::npos) << m;
    EXPECT_NE(m.find("0.3 m"), std::string::npos) << m;
  }
  {
    const Scene scene = curved_room(dir, {false, false, false}, 16);
    dir.write("scene.obj", curved_room_obj({false, false, false}, 0.3f));
    try {
      load_scene(dir.file("scene.json"));
      FAIL() << "a curved wall modelled as a solid was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("modelled as a solid"), std::string::npos) << e.what();
    }
    const double a = scene.domain.element_size();
    const Panel& panel = scene.domain.panels()[0];
    for (const PanelRectangle& bad : {PanelRectangle{0, -2.0, 0.5, 0.5, 1.0},
                                      PanelRectangle{0, 0.5, 1.0, 0.5, (panel.rows + 3) * a},
                                      PanelRectangle{1, 0.5, 1.0, 0.5, 1.0}, PanelRectangle{0, 1.0, 0.5, 0.5, 1.0},
                                      PanelRectangle{0, 0.5, std::nan(""), 0.5, 1.0}}) {
      try {
        evaluate_openings(scene, {OpeningInput(bad)});
        FAIL() << "rectangle u " << bad.u0 << ".." << bad.u1 << ", v " << bad.v0 << ".." << bad.v1 << " on panel "
               << bad.panel << " was accepted";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("opening 0"), std::string::npos) << e.what();
      }
    }
    // Corners are for flat panels: four points on the curved wall are refused, pointing to the other form.
    const Rectangle corners = scene.domain.elements()[0].corners;
    try {
      evaluate_openings(scene, {OpeningInput(corners)});
      FAIL() << "corners on a curved panel were accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("parameter_rectangle"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fenestra
