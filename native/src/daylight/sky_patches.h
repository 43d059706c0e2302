#pragma once
// The sky discretisation of the daylight-coefficient method, as Radiance defines it (reinhart.cal,
// tregenza.cal, gendaymtx): patch 0 is the ground (the whole lower hemisphere); patches 1.. are the
// sky, in rings of equal altitude height from the horizon up, each ring starting with the patch
// centred on true north and going on clockwise seen from above (north, east, south, west); the last
// patch is the zenith cap. Subdivision 1 is Tregenza's 145 patches; subdivision MF (Reinhart)
// splits every Tregenza ring into MF rings of MF times as many patches and keeps one zenith cap:
// 144 MF^2 + 1 sky patches (577 for MF 2, 2305 for MF 4).
//
// Angles: altitude above the horizon and azimuth clockwise from TRUE north seen from above, both
// in radians. World directions: +Z up; true north lies north_offset_deg clockwise from +Y seen from
// above (DaylightSettings::north_offset_deg), so with offset 0, +Y is north and +X east.
// Patches are fixed to true north: patch k is the same piece of the real sky whatever the offset.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "math/vec.h"

namespace fenestra {

using Vec3d = Eigen::Vector3d;

class SkyPatches {
 public:
  // Patches per Tregenza ring, horizon to the last ring below the zenith cap.
  static constexpr int kTregenzaRings = 7;
  static constexpr int kTregenzaRingSizes[kTregenzaRings] = {30, 30, 24, 24, 18, 12, 6};
  static constexpr int kMaxSubdivision = 64;  // 589 825 sky patches: far beyond any practical use
  static constexpr int kGround = 0;

  // Throws std::invalid_argument for a subdivision outside [1, kMaxSubdivision] or a north offset
  // that is not a finite number of degrees.
  explicit SkyPatches(int subdivision = 1, double north_offset_deg = 0.0);

  int subdivision() const { return subdivision_; }
  double north_offset_deg() const { return north_offset_deg_; }
  int count() const { return sky_count_ + 1; }  // with the ground, patch 0
  int sky_count() const { return sky_count_; }

  // Rings: 0 at the horizon, ring_count() - 1 the zenith cap. All rings but the cap span
  // ring_height() of altitude; the cap spans half of it, so that 7 MF + 1/2 rings fill 90 degrees.
  int ring_count() const { return static_cast<int>(ring_sizes_.size()); }
  double ring_height() const { return ring_height_; }  // radians: 90 deg / (7 MF + 1/2)
  int ring_size(int ring) const;
  int first_patch(int ring) const;  // index of the ring's patch centred on true north
  int ring_of(int patch) const;     // -1 for the ground

  // Patch seen in world direction `dir` (any length but zero, finite). Below the horizon
  // (dir.z() < 0) is the ground; the horizon itself (z = 0) belongs to the first ring, as in
  // reinhart.cal. Constant time. Throws std::invalid_argument for a zero or non-finite dir.
  int patch_of(const Vec3d& dir) const;
  int patch_of(const Vec3& dir) const { return patch_of(Vec3d(dir.cast<double>())); }

  // Altitude and azimuth (clockwise from true north, radians) of a world direction.
  double altitude(const Vec3d& dir) const;
  double azimuth(const Vec3d& dir) const;  // in [0, 2 pi)
  // Unit world direction of an altitude and a true azimuth (radians).
  Vec3d direction(double altitude, double azimuth) const;

  // A patch is the set of directions with alt0 <= altitude < alt1 (the cap also holds the zenith,
  // alt1 = pi / 2) and azimuth in [az0, az1) modulo 2 pi. Ring patch j spans azimuths
  // (j -/+ 1/2) x 2 pi / ring_size, so the first patch of a ring has az0 < 0. The zenith cap and
  // the ground span azimuths [-pi, pi).
  struct Bounds {
    double alt0 = 0.0, alt1 = 0.0, az0 = 0.0, az1 = 0.0;  // radians
  };
  Bounds bounds(int patch) const;
  // sr: (sin alt1 - sin alt0)(az1 - az0); the ground is 2 pi, the sky patches sum to 2 pi.
  double solid_angle(int patch) const;
  // sr: the integral of |cos theta| over the patch, (az1 - az0)(sin^2 alt1 - sin^2 alt0) / 2: the
  // horizontal illuminance of a unit luminance over it. The sky patches sum to pi; the ground is pi.
  double projected_solid_angle(int patch) const;
  // Unit world direction of the patch centre as gendaymtx places it: mid-altitude of the ring and
  // the centre azimuth; the zenith for the cap, the nadir for the ground.
  Vec3d centre(int patch) const;

  // Mean of f over each sky patch, in sky-patch order with the ground (index 0) set to 0: the
  // midpoint rule with n x n points on the patch's equal-area grid (azimuth and sin altitude
  // split in n equal steps). Exact for f linear in sin altitude and constant in azimuth; for a
  // smooth f the error falls as 1 / n^2 (docs/sky.md). Throws std::invalid_argument for n < 1.
  std::vector<double> patch_means(const std::function<double(const Vec3d&)>& f, int points_per_side = 4) const;

  // Uniform directions within a patch (the ground included), Mitsuba's triplet: (u, v) in
  // [0, 1)^2 maps linearly to azimuth and to sin altitude, so the density is 1 / solid_angle.
  Vec3d square_to_patch(int patch, double u, double v) const;
  double square_to_patch_pdf(int patch) const { return 1.0 / solid_angle(patch); }  // 1/sr
  Eigen::Vector2d patch_to_square(int patch, const Vec3d& dir) const;  // inverse on the patch

  std::string to_string() const;

 private:
  void check_patch(int patch, const char* caller) const;
  double ring_alt0(int ring) const { return ring * ring_height_; }
  double ring_alt1(int ring) const;

  int subdivision_;
  double north_offset_deg_, north_offset_rad_;
  double ring_height_;
  std::vector<int> ring_sizes_;     // patches per ring
  std::vector<int> ring_first_;     // first patch index of each ring, then sky_count_ + 1
  std::vector<int> patch_ring_;     // ring of each patch, -1 for the ground
  int sky_count_ = 0;
};

}  // namespace fenestra
