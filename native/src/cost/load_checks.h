#pragma once
// Cost checks made while a scene is read, before the large allocations of reading it: the OBJ
// file, the dicing of the opening domain, an environment map's pixels, a daylight sky's steps, a
// climate's sky matrix.
// Each throws CostError (a std::invalid_argument; the loader prefixes the scene and the key)
// naming the estimated figure, the limit and the setting to change. Limits: cost/memory_limit.h.
#include <cstdint>
#include <string>
#include <vector>

namespace fenestra {

struct Mesh;
struct DaylightSettings;

// Reading an OBJ needs about 12 times its size (its text twice, tinyobjloader's arrays, the
// mesh); measured 6.8x on a 38 MB file of a million triangles, more for files of short lines.
void check_geometry_file_cost(const std::string& path);

// The opening domain before it is diced: per panel (coplanar triangles), its area and the grid
// of squares over its bounding rectangle.
struct DomainEstimate {
  double elements = 0.0;      // sum over panels of min(area / size^2, grid cells)
  double grid_cells = 0.0;    // sum over panels of rows x cols
  double largest_side = 0.0;  // meters: the largest panel's longer side
};
DomainEstimate estimate_domain(const Mesh& mesh, const std::vector<std::vector<uint32_t>>& panels, float element_size);
// The domain's own arrays, and, when the command computes them (cost/cost_context.h), the matrix
// T (elements x elements doubles, counted twice: the margin of the largest studies). Whatever the command, at most
// kMaxElements: dicing takes about 1 us per element (an OBJ in millimetres gave 48 million
// elements, 57 s and 6.9 GB before an evaluate that does not use them), and T alone would need
// 8 TB: such a domain can never be solved.
inline constexpr double kMaxElements = 1e6;
void check_domain_cost(const DomainEstimate& estimate, float element_size);

// Environment maps: at most kMaxImagePixels pixels, and their reading must fit in memory
// (the file's floats, the map, its sampling distribution: 4 x channels + 52 bytes per pixel).
inline constexpr double kMaxImagePixels = 16384.0 * 8192.0;
void check_image_cost(const std::string& path, int width, int height, int channels);

// A daylight sky: building it must fit in memory (80 bytes per map pixel) and take at most
// kMaxDaylightSeconds on the reference machine (each step with the sun up rasterises the upper
// half of the map, about 40 ns per pixel, and creates its sky: 2 ms, 0.2 ms for a Perez sky).
inline constexpr double kMaxDaylightSeconds = 300.0;
double daylight_build_seconds(const DaylightSettings& settings, size_t* steps = nullptr, size_t* steps_with_sun = nullptr);
void check_daylight_cost(const DaylightSettings& settings);

// A climate's sky matrix (daylight/sky_matrix.h): its patches x hours floats and per-hour vectors
// must fit in memory, and its patch means (points^2 Perez evaluations per sky patch for every hour
// with light) take at most kMaxSkyMatrixSeconds on the reference machine.
inline constexpr double kMaxSkyMatrixSeconds = 300.0;
double sky_matrix_bytes(int patches, size_t hours);
double sky_matrix_build_seconds(int patches, size_t hours_with_light, int points_per_side);
void check_sky_matrix_cost(int subdivision, int patches, size_t hours, size_t hours_with_light, int points_per_side);

}  // namespace fenestra
