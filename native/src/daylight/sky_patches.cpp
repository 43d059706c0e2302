#include "daylight/sky_patches.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "math/constants.h"
#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr double kTwoPi = 2.0 * kPiD;

// Angle in [0, 2 pi).
double wrap_angle(double a) {
  a = std::fmod(a, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a < kTwoPi ? a : 0.0;  // -tiny + 2 pi rounds to 2 pi
}

void check_direction(const Vec3d& dir, const char* caller) {
  if (!std::isfinite(dir.x()) || !std::isfinite(dir.y()) || !std::isfinite(dir.z()) || dir.squaredNorm() == 0.0) {
    std::ostringstream s;
    s << "SkyPatches::" << caller << ": direction (" << dir.x() << ", " << dir.y() << ", " << dir.z()
      << ") must be finite and not zero";
    throw std::invalid_argument(s.str());
  }
}

}  // namespace

SkyPatches::SkyPatches(int subdivision, double north_offset_deg)
    : subdivision_(subdivision), north_offset_deg_(north_offset_deg) {
  if (subdivision < 1 || subdivision > kMaxSubdivision)
    throw std::invalid_argument("SkyPatches: subdivision " + std::to_string(subdivision) +
                                " must be an integer in [1, " + std::to_string(kMaxSubdivision) +
                                "] (1: Tregenza's 145 patches; 2: 577; 4: 2305)");
  if (!std::isfinite(north_offset_deg))
    throw std::invalid_argument("SkyPatches: north_offset_deg " + decimal_text(north_offset_deg) +
                                " must be a finite number of degrees");
  north_offset_rad_ = north_offset_deg * kPiD / 180.0;
  ring_height_ = 0.5 * kPiD / (kTregenzaRings * subdivision + 0.5);
  for (int t = 0; t < kTregenzaRings; ++t)
    for (int k = 0; k < subdivision; ++k) ring_sizes_.push_back(kTregenzaRingSizes[t] * subdivision);
  ring_sizes_.push_back(1);  // the zenith cap
  patch_ring_.push_back(-1);  // the ground
  int first = 1;
  for (int r = 0; r < ring_count(); ++r) {
    ring_first_.push_back(first);
    first += ring_sizes_[r];
    patch_ring_.insert(patch_ring_.end(), ring_sizes_[r], r);
  }
  ring_first_.push_back(first);
  sky_count_ = first - 1;
}

int SkyPatches::ring_size(int ring) const {
  if (ring < 0 || ring >= ring_count())
    throw std::invalid_argument("SkyPatches::ring_size: ring " + std::to_string(ring) + " is outside [0, " +
                                std::to_string(ring_count() - 1) + "]");
  return ring_sizes_[ring];
}

int SkyPatches::first_patch(int ring) const {
  if (ring < 0 || ring >= ring_count())
    throw std::invalid_argument("SkyPatches::first_patch: ring " + std::to_string(ring) + " is outside [0, " +
                                std::to_string(ring_count() - 1) + "]");
  return ring_first_[ring];
}

int SkyPatches::ring_of(int patch) const {
  check_patch(patch, "ring_of");
  return patch_ring_[patch];
}

void SkyPatches::check_patch(int patch, const char* caller) const {
  if (patch < 0 || patch >= count())
    throw std::invalid_argument(std::string("SkyPatches::") + caller + ": patch " + std::to_string(patch) +
                                " is outside [0, " + std::to_string(count() - 1) + "] (0: the ground)");
}

double SkyPatches::ring_alt1(int ring) const {
  return ring == ring_count() - 1 ? 0.5 * kPiD : (ring + 1) * ring_height_;
}

double SkyPatches::altitude(const Vec3d& dir) const {
  check_direction(dir, "altitude");
  return std::atan2(dir.z(), std::hypot(dir.x(), dir.y()));  // better conditioned than asin near the zenith
}

double SkyPatches::azimuth(const Vec3d& dir) const {
  check_direction(dir, "azimuth");
  // atan2(x, y) is clockwise from +Y seen from above; true north is north_offset further clockwise.
  return wrap_angle(std::atan2(dir.x(), dir.y()) - north_offset_rad_);
}

Vec3d SkyPatches::direction(double altitude, double azimuth) const {
  const double c = std::cos(altitude), w = azimuth + north_offset_rad_;
  return Vec3d(c * std::sin(w), c * std::cos(w), std::sin(altitude));
}

int SkyPatches::patch_of(const Vec3d& dir) const {
  const double alt = altitude(dir);
  if (dir.z() < 0.0) return kGround;
  const int ring = std::min(static_cast<int>(alt / ring_height_), ring_count() - 1);
  const int n = ring_sizes_[ring];
  if (n == 1) return ring_first_[ring];
  const double step = kTwoPi / n;
  const double shifted = wrap_angle(azimuth(dir) + 0.5 * step);  // patch j starts at (j - 1/2) step
  return ring_first_[ring] + std::min(static_cast<int>(shifted / step), n - 1);
}

SkyPatches::Bounds SkyPatches::bounds(int patch) const {
  check_patch(patch, "bounds");
  const int ring = patch_ring_[patch];
  if (ring < 0) return Bounds{-0.5 * kPiD, 0.0, -kPiD, kPiD};
  const int n = ring_sizes_[ring];
  Bounds b{ring_alt0(ring), ring_alt1(ring), -kPiD, kPiD};
  if (n > 1) {
    const double step = kTwoPi / n;
    const int j = patch - ring_first_[ring];
    b.az0 = (j - 0.5) * step;
    b.az1 = (j + 0.5) * step;
  }
  return b;
}

double SkyPatches::solid_angle(int patch) const {
  const Bounds b = bounds(patch);
  return (std::sin(b.alt1) - std::sin(b.alt0)) * (b.az1 - b.az0);
}

double SkyPatches::projected_solid_angle(int patch) const {
  const Bounds b = bounds(patch);
  const double s0 = std::sin(b.alt0), s1 = std::sin(b.alt1);
  return std::abs(0.5 * (s1 - s0) * (s1 + s0) * (b.az1 - b.az0));
}

Vec3d SkyPatches::centre(int patch) const {
  const Bounds b = bounds(patch);
  const int ring = patch_ring_[patch];
  if (ring < 0) return Vec3d(0.0, 0.0, -1.0);
  if (ring_sizes_[ring] == 1) return Vec3d(0.0, 0.0, 1.0);
  return direction(0.5 * (b.alt0 + b.alt1), 0.5 * (b.az0 + b.az1));
}

Vec3d SkyPatches::square_to_patch(int patch, double u, double v) const {
  if (!(u >= 0.0 && u <= 1.0) || !(v >= 0.0 && v <= 1.0))
    throw std::invalid_argument("SkyPatches::square_to_patch: (u, v) = (" + decimal_text(u) + ", " + decimal_text(v) +
                                ") must lie in [0, 1]^2");
  const Bounds b = bounds(patch);
  const double s0 = std::sin(b.alt0), s1 = std::sin(b.alt1);
  const double s = s0 + v * (s1 - s0);              // sin altitude: uniform in solid angle
  const double c = std::sqrt(std::max(0.0, (1.0 - s) * (1.0 + s)));  // cos altitude, exact near the zenith
  const double w = b.az0 + u * (b.az1 - b.az0) + north_offset_rad_;
  return Vec3d(c * std::sin(w), c * std::cos(w), s);
}

Eigen::Vector2d SkyPatches::patch_to_square(int patch, const Vec3d& dir) const {
  check_direction(dir, "patch_to_square");
  const Bounds b = bounds(patch);
  const double s0 = std::sin(b.alt0), s1 = std::sin(b.alt1);
  const double s = dir.z() / dir.norm();
  const double from_az0 = wrap_angle(azimuth(dir) - b.az0);
  return Eigen::Vector2d(from_az0 / (b.az1 - b.az0), (s - s0) / (s1 - s0));
}

std::vector<double> SkyPatches::patch_means(const std::function<double(const Vec3d&)>& f,
                                            int points_per_side) const {
  if (points_per_side < 1)
    throw std::invalid_argument("SkyPatches::patch_means: points_per_side " + std::to_string(points_per_side) +
                                " must be 1 or more");
  const int n = points_per_side;
  std::vector<double> means(count(), 0.0);
  for (int p = 1; p < count(); ++p) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) sum += f(square_to_patch(p, (i + 0.5) / n, (j + 0.5) / n));
    means[p] = sum / (double(n) * n);
  }
  return means;
}

std::string SkyPatches::to_string() const {
  std::ostringstream s;
  s << "SkyPatches(" << (subdivision_ == 1 ? std::string("Tregenza") : "Reinhart MF " + std::to_string(subdivision_))
    << ": " << sky_count_ << " sky patches + ground, " << ring_count() << " rings of " << ring_height_ * 180.0 / kPiD
    << " deg, north offset " << north_offset_deg_ << " deg)";
  return s.str();
}

}  // namespace fenestra
