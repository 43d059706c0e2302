#pragma once
// Small scenes written to a temporary directory, for tests with analytic answers.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "math/vec.h"
#include "scene/scene.h"
#include "student_t.h"
#include "trace/replicates.h"

namespace fenestra::test {

// The Chicago O'Hare TMY3 weather file of the examples.
inline const std::string kChicago =
    std::string(FENESTRA_EXAMPLES) + "/weather/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("fenestra_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(file(name)) << text; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// An opening domain made of the given quads (corners counter-clockwise seen from the normal's
// side), all of material "domain".
inline OpeningDomain domain_of_quads(const std::vector<std::array<Vec3, 4>>& quads, float element_size) {
  Mesh mesh;
  for (const auto& q : quads) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), q.begin(), q.end());
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
    mesh.triangle_material.insert(mesh.triangle_material.end(), 2, 0);
    mesh.triangle_group.insert(mesh.triangle_group.end(), 2, -1);
  }
  OpeningDomainSelection selection;
  selection.materials = {"domain"};
  selection.element_size = element_size;
  return OpeningDomain::build(mesh, {"domain"}, selection);
}

// OBJ text built from quads; each quad is its own group with a material.
class ObjBuilder {
 public:
  void quad(const std::string& group, const std::string& material, const Vec3& p0, const Vec3& p1, const Vec3& p2,
            const Vec3& p3) {
    s_ << "o " << group << "\nusemtl " << material << "\n";
    for (const Vec3* p : {&p0, &p1, &p2, &p3}) s_ << "v " << p->x() << " " << p->y() << " " << p->z() << "\n";
    s_ << "f " << n_ + 1 << " " << n_ + 2 << " " << n_ + 3 << " " << n_ + 4 << "\n";
    n_ += 4;
  }
  // Axis-aligned closed box; `material_of(face)` with face in {floor, ceiling, south, north, west, east}.
  template <typename F>
  void box(const Vec3& lo, const Vec3& hi, F material_of) {
    const float x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
    quad("floor", material_of("floor"), {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0});
    quad("ceiling", material_of("ceiling"), {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1});
    quad("south", material_of("south"), {x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1});
    quad("north", material_of("north"), {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0});
    quad("west", material_of("west"), {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0});
    quad("east", material_of("east"), {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1});
  }
  std::string str() const { return s_.str(); }

 private:
  std::ostringstream s_;
  int n_ = 0;
};

// Rays leave a sensor from 0.1 mm along its normal (the tracer's ray offset); the stratified
// estimates are precise enough to see it, so closed forms are evaluated there too.
constexpr float kSensorLift = 1e-4f;

// Relative precision of single-precision path values summed in double: a floor for estimates
// whose Monte Carlo variance vanishes.
constexpr double kFloatRounding = 1e-6;

// View factor from a differential area at p with unit normal n to a planar polygon wholly in
// front of it (Lambert's closed form: sum over edges of the angle they subtend times n . edge normal).
inline double polygon_view_factor(const Vec3& p, const Vec3& n, const std::vector<Vec3>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d a = (polygon[i] - p).cast<double>().normalized();
    const Eigen::Vector3d b = (polygon[(i + 1) % polygon.size()] - p).cast<double>().normalized();
    const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    sum += angle * n.cast<double>().dot(a.cross(b).normalized());
  }
  return std::abs(sum) / (2.0 * M_PI);
}

// Differential area to a parallel rectangle a x b at distance c, the normal through one corner
// (the classical corner formula, e.g. Howell's catalogue B-3).
inline double parallel_corner_view_factor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * M_PI);
}

// Elements whose centres lie inside the axis-aligned rectangle r (an opening in world coordinates).
inline std::vector<uint8_t> mask_of_elements_inside(const Scene& scene, const std::array<Vec3, 4>& r) {
  const Vec3 lo = r[0].cwiseMin(r[2]), hi = r[0].cwiseMax(r[2]);
  std::vector<uint8_t> mask(scene.domain.element_count(), 0);
  for (size_t k = 0; k < mask.size(); ++k) {
    const Vec3 c = scene.domain.elements()[k].center;
    mask[k] = (c.array() >= lo.array() - 1e-4f).all() && (c.array() <= hi.array() + 1e-4f).all();
  }
  return mask;
}

// The reference room's irradiance, all bounces (../shared/reference/radiance-scene-b.md: Radiance
// 6.1a and radiosity, within 0.3 %), sensors in the order of examples/reference_room.
inline constexpr double kReferenceRoomTable[16] = {66.90, 258.96, 258.96, 66.90, 50.68, 81.13, 81.13, 50.68,
                                                   30.73, 36.73, 36.73, 30.73, 22.83, 25.33, 25.33, 22.83};

// |a - b| within k combined standard errors, k read as the false-alarm rate of a normal k sigma.
// Each standard error is estimated from kReplicates groups (kReplicates - 1 degrees of freedom),
// so the bound is the Student t quantile of that rate at the Welch-Satterthwaite degrees of
// freedom of the combination (a normal bound would claim a false-alarm rate ten times too low).
inline ::testing::AssertionResult within_sigma(double a, double sa, double b, double sb, double k = 4.0) {
  const double sigma = std::sqrt(sa * sa + sb * sb);
  constexpr double nu_each = static_cast<double>(kReplicates - 1);
  const double nu = sigma > 0.0 ? std::pow(sigma, 4) / ((std::pow(sa, 4) + std::pow(sb, 4)) / nu_each) : nu_each;
  const double bound = normal_equivalent_t(k, nu);
  if (std::abs(a - b) <= bound * sigma) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " and " << b << " differ by " << std::abs(a - b) << " > " << bound
                                       << " x " << sigma << " (combined standard error; t quantile of a normal " << k
                                       << " sigma at " << nu << " degrees of freedom)";
}

// A 4 x 3 x 2.5 m room whose south wall and ceiling are the opening domain (0.5 m elements), a
// neighbouring building 4 m south, four sensors, a Preetham sky at 11:00.
inline Scene room_with_neighbour(const TempDir& dir, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {4, 3, 2.5f}, [](const std::string& f) { return f == "south" || f == "ceiling" ? "domain" : "grey"; });
  obj.quad("ground", "ground", {-30, -30, -0.01f}, {30, -30, -0.01f}, {30, 30, -0.01f}, {-30, 30, -0.01f});
  obj.quad("neighbour", "grey", {-5, -4, 0}, {-5, -4, 6}, {8, -4, 6}, {8, -4, 0});
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj",
      "materials": {"grey": {"reflectance": 0.6}, "domain": {"reflectance": 0.5}, "ground": {"reflectance": 0.2}},
      "opening_domain": {"materials": ["domain"], "element_size": 0.5},
      "sensors": {"points": [[1, 1, 0.8], [3, 2, 0.8], [2, 2.5, 1.2], [0.5, 0.5, 2]], "normals": [0, 0, 1]},
      "sky": {"type": "preetham", "latitude": 48.85, "longitude": 2.35, "utc_offset": 1, "date": "2026-03-21",
              "time": "11:00", "resolution": [128, 64]},
      "render": {"paths_per_sensor": )"
    << paths << R"(, "max_bounces": 6, "seed": 5}})";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

}  // namespace fenestra::test
