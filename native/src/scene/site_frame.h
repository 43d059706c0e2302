#pragma once
// Where the scene's local frame sits in the coordinates the user gave (site coordinates).
//
// Models arrive in projected site coordinates (UTM: eastings near 5e5 m, northings up to 1e7 m),
// where a float keeps only 0.06-1 m: rays leave surfaces through offsets of 1e-4 m and would leak.
// Every position is therefore read in double, shifted by a local origin near the model, and only
// then stored in float (what Embree consumes); outputs shift back in double. The origin is a whole
// number of meters, so the shift is exact both ways, and a model moved by whole meters (away from
// the origin) gets the same local coordinates, and so the same numbers, wherever it lies.
#include <Eigen/Core>
#include <string>

#include "math/vec.h"

namespace fenestra {

using Vec3d = Eigen::Vector3d;

struct SiteFrame {
  Vec3d origin = Vec3d::Zero();  // meters, in the input's coordinates; whole meters

  // A model whose bounding box (lo, hi, input coordinates) lies within +-kNearOrigin of the origin
  // is traced as given (its floats keep 1.5e-5 m); any other is centred: the origin is the box's
  // centre rounded to whole meters.
  static constexpr double kNearOrigin = 128.0;
  static SiteFrame around(const Vec3d& lo, const Vec3d& hi);

  bool shifted() const { return origin != Vec3d::Zero(); }
  Vec3d to_local_exact(const Vec3d& site) const { return site - origin; }
  Vec3 to_local(const Vec3d& site) const { return (site - origin).cast<float>(); }
  Vec3d to_site(const Vec3& local) const { return local.cast<double>() + origin; }
  std::string to_string() const;  // "SiteFrame(origin=[x, y, z] m)"
};

}  // namespace fenestra
