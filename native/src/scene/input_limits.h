#pragma once
// The accepted range of every number a user gives Fenestra (scene file, OBJ, openings file,
// command line, Python setters), in one place so that every entry point checks the same limits.
// docs/scene-format.md ("Accepted ranges") lists them.
#include <cstdint>
#include <string>

#include "math/vec.h"
#include "scene/site_frame.h"

namespace fenestra {

// An integer setting and its closed range; `key` names it in messages.
struct IntegerRange {
  const char* key;
  long long lo, hi;
  bool contains(long long v) const { return v >= lo && v <= hi; }
  // "must be an integer in [lo, hi]"
  std::string requirement() const;
};

namespace limits {

// |x|, meters, in the coordinates the user gives (site coordinates, up to UTM northings): sensor
// points, OBJ vertices, opening corners. Read in double.
inline constexpr double kMaxCoordinate = 1e7;
// |x - origin|, meters: how far any position may lie from the scene's local origin
// (scene/site_frame.h), the centre of its model: a float keeps 0.06 m there.
inline constexpr double kMaxLocalCoordinate = 1e6;
// |x|: the components of a sensor normal (normalized in double), and sky.elevation in meters.
inline constexpr double kMaxNormalComponent = 1e6;
inline constexpr double kMaxElevation = 1e6;
// cd/m^2: a uniform sky's radiance, an environment map's pixels times its scale, a CIE sky's
// zenith luminance (the sun's disk is about 1.6e9 cd/m^2).
inline constexpr double kMaxRadiance = 1e12;
// lux: a CIE overcast sky's horizontal illuminance, goals in lux.
inline constexpr double kMaxIlluminance = 1e12;
// degrees: sky.rotation_deg and sky.north_offset_deg lie in [-360, 360].
inline constexpr double kMaxTurnDeg = 360.0;
// meters: opening_domain.thickness.
inline constexpr double kMaxThickness = 10.0;
// minutes: sky.step_minutes.
inline constexpr double kMinStepMinutes = 0.1, kMaxStepMinutes = 1440.0;
// sensor weights (relative).
inline constexpr double kMaxWeight = 1e6;

inline constexpr IntegerRange kPathsPerSensor{"render.paths_per_sensor", 1, 1LL << 30};
inline constexpr IntegerRange kMaxBounces{"render.max_bounces", 0, 1000};
inline constexpr IntegerRange kSeed{"render.seed", 0, 1LL << 53};  // exact in a JSON number (a double)
inline constexpr IntegerRange kThreads{"render.threads", 0, 4096};
inline constexpr IntegerRange kSkyWidth{"sky.resolution[0]", 4, 16384};
inline constexpr IntegerRange kSkyHeight{"sky.resolution[1]", 2, 8192};

// Input files are read whole; larger ones are refused before reading.
inline constexpr std::uintmax_t kMaxSceneFileBytes = 256ull << 20;     // scene and openings JSON
inline constexpr std::uintmax_t kMaxGeometryFileBytes = 2ull << 30;    // OBJ
inline constexpr std::uintmax_t kMaxImageFileBytes = 2ull << 30;       // environment maps
inline constexpr std::uintmax_t kMaxWeatherFileBytes = 256ull << 20;   // .epw, .wea (a year of hours: 1.6 MB)

}  // namespace limits

// Whether a coordinate (meters) is finite and within +-limits::kMaxCoordinate.
inline bool coordinate_in_range(double v) { return v >= -limits::kMaxCoordinate && v <= limits::kMaxCoordinate; }
inline bool coordinates_in_range(const Vec3& p) {
  return coordinate_in_range(p.x()) && coordinate_in_range(p.y()) && coordinate_in_range(p.z());
}
// "must be finite and within +-1e+07 m"
std::string coordinate_requirement();
// Whether a position relative to the local origin (meters) lies within +-limits::kMaxLocalCoordinate.
inline bool local_coordinates_in_range(const Vec3d& p) {
  return p.cwiseAbs().maxCoeff() <= limits::kMaxLocalCoordinate;
}
// "lies farther than 1e+06 m from the model's local origin [x, y, z] (a scene must fit within +-1e+06 m of it)"
std::string local_range_problem(const Vec3d& origin);

// Refuses (std::invalid_argument naming `what` and the path) a file that does not exist, is not
// a regular file (a directory, a device such as /dev/zero, a FIFO), or is larger than max_bytes.
// Symbolic links are followed.
void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

}  // namespace fenestra
