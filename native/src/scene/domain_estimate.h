#pragma once
// The opening domain's size before it is diced, and the refusal of a domain too large to dice or
// to solve (CostError naming the figure and the setting to change; util/memory_limit.h).
#include <cstdint>
#include <vector>

namespace fenestra {

struct Mesh;

// Per panel (coplanar triangles), its area and the grid of squares over its bounding rectangle.
struct DomainEstimate {
  double elements = 0.0;      // sum over panels of min(area / size^2, grid cells)
  double grid_cells = 0.0;    // sum over panels of rows x cols
  double largest_side = 0.0;  // meters: the largest panel's longer side
};
DomainEstimate estimate_domain(const Mesh& mesh, const std::vector<std::vector<uint32_t>>& panels, float element_size);
// The domain's own arrays, and, when the command computes them (util/cost_context.h), the matrix
// T (elements x elements doubles, counted twice: the margin of the largest studies). Whatever the command, at most
// kMaxElements: dicing takes about 1 us per element (an OBJ in millimetres gave 48 million
// elements, 57 s and 6.9 GB before an evaluate that does not use them), and T alone would need
// 8 TB: such a domain can never be solved.
inline constexpr double kMaxElements = 1e6;
void check_domain_cost(const DomainEstimate& estimate, float element_size);

}  // namespace fenestra
