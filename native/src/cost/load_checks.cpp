#include "cost/load_checks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "cost/byte_size.h"
#include "cost/cost_context.h"
#include "cost/cost_model.h"
#include "cost/element_size_hint.h"
#include "cost/memory_limit.h"
#include "daylight/daylight.h"
#include "daylight/weather_file.h"
#include "scene/mesh.h"
#include "scene/opening_domain.h"
#include "util/quoted_text.h"

namespace fenestra {
namespace {

constexpr double kObjBytesPerFileByte = 12.0;
// Element (trace/opening_domain.h) with the vector's spare capacity, per element; int per grid cell.
constexpr double kDomainBytesPerElement = 2.0 * sizeof(Element), kDomainBytesPerCell = sizeof(int);
constexpr double kDaylightBytesPerPixel = 80.0;
constexpr double kDaylightSecondsPerPixel = 40e-9, kDaylightSecondsPerStep = 5e-6;
// Per step with light, besides its pixels: the model's creation, its horizontal illuminance by
// quadrature (96 x 192 directions: Preetham, CIE clear; a Perez sky gives its own) and the sun's
// disk. Measured as CPU time against the pixels' (so that the machine's load cancels): a Preetham or
// CIE clear step costs as much as 24 600 pixels of the map's upper half, 1.0 ms at 40 ns a pixel,
// 1.8 ms measured on the reference machine; a Perez step 3 300 pixels. Rounded up.
constexpr double kDaylightSecondsPerAnalyticStep = 2e-3, kDaylightSecondsPerPerezStep = 0.2e-3;
// The sky matrix: one float per patch and hour, and per hour a HourStamp, a sun direction and
// illuminance, two doubles; the Perez sky of an hour takes about 0.1 ms to create.
constexpr double kSkyMatrixBytesPerHour = sizeof(double) * 2 + 16 + 12 + 4, kSkyMatrixSecondsPerHour = 1e-4;
constexpr double kSkyMatrixSecondsPerEvaluation = 15e-9;  // one luminance of a patch mean, 2 cores
// A domain this large is probably not in meters.
constexpr double kSuspiciousSide = 1000.0;

// The panel's row direction, as OpeningDomain::build chooses it (horizontal on walls and tilted
// roofs, +X on flat roofs).
void panel_axes(const Vec3& n, Vec3* u, Vec3* v) {
  if (std::abs(n.z()) < 0.999f) {
    *u = Vec3(0, 0, 1).cross(n).normalized();
  } else {
    *u = (Vec3(1, 0, 0) - n.x() * n).normalized();
  }
  *v = n.cross(*u);
}

}  // namespace

void check_geometry_file_cost(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  if (error || !std::filesystem::is_regular_file(path, error)) return;  // the reader reports it
  const MemoryLimit limit = memory_limit();
  const double need = kObjBytesPerFileByte * static_cast<double>(size);
  if (need > static_cast<double>(limit.bytes))
    throw CostError("geometry '" + quoted_path(path) + "' is " + format_bytes(static_cast<double>(size)) + "; " +
                    memory_refusal("reading it", need, need, limit, "a smaller geometry file (fewer triangles)"));
}

DomainEstimate estimate_domain(const Mesh& mesh, const std::vector<std::vector<uint32_t>>& panels, float element_size) {
  DomainEstimate out;
  const double s = element_size;
  for (const auto& tris : panels) {
    if (tris.empty()) continue;
    Vec3 n = Vec3::Zero();
    for (uint32_t t : tris) n += mesh.area_normal(t);
    const double area = 0.5 * n.norm();
    if (!(n.norm() > 0.0f)) continue;
    n.normalize();
    Vec3 u, v;
    panel_axes(n, &u, &v);
    const Vec3 o = mesh.vertex(tris.front(), 0);
    double amin = HUGE_VAL, amax = -HUGE_VAL, bmin = HUGE_VAL, bmax = -HUGE_VAL;
    for (uint32_t t : tris)
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = mesh.vertex(t, k) - o;
        const double a = d.dot(u), b = d.dot(v);
        amin = std::min(amin, a), amax = std::max(amax, a), bmin = std::min(bmin, b), bmax = std::max(bmax, b);
      }
    const double cells = std::floor((amax - amin) / s + 1e-4) * std::floor((bmax - bmin) / s + 1e-4);
    out.grid_cells += cells;
    out.elements += std::min(cells, area / (s * s));
    out.largest_side = std::max({out.largest_side, amax - amin, bmax - bmin});
  }
  return out;
}

void check_domain_cost(const DomainEstimate& estimate, float element_size) {
  const MemoryLimit limit = memory_limit();
  const double N = estimate.elements;
  const double domain = kDomainBytesPerElement * N + kDomainBytesPerCell * estimate.grid_cells;
  const bool matrices = needs_element_matrices(cost_context().command);
  const double t = matrices ? 8.0 * N * N : 0.0;
  const double total = domain + 2.0 * t;  // T, and as much again as a margin (cost_model.cpp)
  const bool too_many = N > kMaxElements;
  if (!(total > static_cast<double>(limit.bytes)) && !too_many) return;
  const double cells_per_element = N > 0.0 ? estimate.grid_cells / N : 0.0;
  const double fits = element_size_that_fits(
      element_size, N,
      [&](double n) {
        return (kDomainBytesPerElement + kDomainBytesPerCell * cells_per_element) * n + (matrices ? 16.0 * n * n : 0.0);
      },
      static_cast<double>(limit.bytes), kMaxElements);
  std::ostringstream s;
  s << "element_size " << element_size << " m gives about " << format_count(N, 3) << " elements";
  if (estimate.largest_side > kSuspiciousSide)
    s << " (a panel of the opening domain is " << format_count(estimate.largest_side, 3)
      << " m long: is the geometry in millimetres? OBJ coordinates are read as meters)";
  s << "; ";
  const std::string setting = larger_element_size(fits);
  if (too_many && !(total > static_cast<double>(limit.bytes)))
    s << "at most " << format_count(kMaxElements) << " elements are diced (about 1 us each; their matrix T alone would need "
      << format_bytes(8.0 * kMaxElements * kMaxElements) << "): use " << setting;
  else if (t >= domain)
    s << memory_refusal("the error-compensation matrix T alone", t, total, limit, setting);
  else
    s << memory_refusal("the opening domain's grid", domain, total, limit, setting);
  throw CostError(s.str());
}

void check_image_cost(const std::string& path, int width, int height, int channels) {
  const double pixels = static_cast<double>(width) * static_cast<double>(height);
  const double need = pixels * (4.0 * std::max(channels, 1) + 52.0);
  std::ostringstream s;
  s << "environment map '" << path << "' is " << width << " x " << height << " pixels";
  if (pixels > kMaxImagePixels) {
    s << " (" << format_count(pixels) << "; reading it would need " << format_bytes(need) << "): at most "
      << format_count(kMaxImagePixels) << " pixels (16384 x 8192) are read: use a smaller map";
    throw CostError(s.str());
  }
  const MemoryLimit limit = memory_limit();
  if (need > static_cast<double>(limit.bytes)) {
    s << "; " << memory_refusal("reading it", need, need, limit, "a smaller map");
    throw CostError(s.str());
  }
}

double daylight_build_seconds(const DaylightSettings& settings, size_t* steps_out, size_t* up_out) {
  size_t steps = 1, up = 1, lit = 1;
  const bool perez = settings.model == DaylightSettings::Model::Perez;
  if (settings.model != DaylightSettings::Model::CieOvercast) {
    const std::vector<TimeStep> list = time_steps(settings);
    steps = list.size(), up = 0, lit = 0;
    for (const TimeStep& step : list) {
      const bool sun_up = solar_position(step.utc_seconds, settings.place, true).zenith_deg < 90.0;
      up += sun_up;
      // A weather file's twilight rows light the Perez sky too (daylight.cpp).
      lit += sun_up || (perez && settings.weather && step.weather_row >= 0 &&
                        settings.weather->hours[static_cast<size_t>(step.weather_row)].diffuse_horizontal_w_m2 > 0.0);
    }
  }
  if (steps_out) *steps_out = steps;
  if (up_out) *up_out = up;
  const double upper_pixels = static_cast<double>(settings.width) * (settings.height / 2);
  const double per_step = perez ? kDaylightSecondsPerPerezStep : kDaylightSecondsPerAnalyticStep;
  return static_cast<double>(lit) * (upper_pixels * kDaylightSecondsPerPixel + per_step) +
         static_cast<double>(steps) * kDaylightSecondsPerStep;
}

void check_daylight_cost(const DaylightSettings& settings) {
  const double pixels = static_cast<double>(settings.width) * settings.height;
  const MemoryLimit limit = memory_limit();
  const double need = kDaylightBytesPerPixel * pixels;
  std::ostringstream s;
  if (need > static_cast<double>(limit.bytes)) {
    s << "resolution " << settings.width << " x " << settings.height << ": "
      << memory_refusal("building the sky map", need, need, limit, "a smaller sky.resolution");
    throw CostError(s.str());
  }
  size_t steps = 0, up = 0;
  const double seconds = daylight_build_seconds(settings, &steps, &up);
  if (seconds <= kMaxDaylightSeconds) return;
  s << "the interval needs " << format_count(static_cast<double>(steps)) << " time steps of " << settings.step_minutes
    << " min (" << format_count(static_cast<double>(up)) << " with the sun up) at " << settings.width << " x "
    << settings.height << " pixels: building the sky would take about " << std::lround(seconds / 60.0) << " min ("
    << format_count(seconds) << " s on the 2-core reference machine; at most " << format_count(kMaxDaylightSeconds)
    << " s): use a larger sky.step_minutes, a shorter interval (sky.date_end, sky.start, sky.end) or a smaller "
       "sky.resolution";
  throw CostError(s.str());
}

double sky_matrix_bytes(int patches, size_t hours) {
  return (4.0 * patches + kSkyMatrixBytesPerHour) * static_cast<double>(hours);
}

double sky_matrix_build_seconds(int patches, size_t hours_with_light, int points_per_side) {
  const double evaluations = static_cast<double>(patches) * points_per_side * points_per_side;
  return static_cast<double>(hours_with_light) * (evaluations * kSkyMatrixSecondsPerEvaluation + kSkyMatrixSecondsPerHour);
}

void check_sky_matrix_cost(int subdivision, int patches, size_t hours, size_t hours_with_light, int points_per_side) {
  const MemoryLimit limit = memory_limit();
  const double need = sky_matrix_bytes(patches, hours);
  std::ostringstream s;
  s << "patches " << subdivision << " gives " << format_count(patches) << " patches x " << format_count(static_cast<double>(hours))
    << " hours: ";
  if (need > static_cast<double>(limit.bytes)) {
    s << memory_refusal("the sky matrix", need, need, limit, "fewer sky patches (sky.patches 1, 2 or 4)");
    throw CostError(s.str());
  }
  const double seconds = sky_matrix_build_seconds(patches, hours_with_light, points_per_side);
  if (seconds <= kMaxSkyMatrixSeconds) return;
  s << "building the sky matrix would take about " << std::lround(seconds / 60.0) << " min ("
    << format_count(seconds) << " s on the 2-core reference machine; at most " << format_count(kMaxSkyMatrixSeconds)
    << " s): use fewer sky patches (sky.patches 1, 2 or 4)";
  throw CostError(s.str());
}

}  // namespace fenestra
