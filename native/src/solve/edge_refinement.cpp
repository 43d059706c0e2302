#include "solve/edge_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "solve/region_search.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr double kTolerance = 1e-6;  // meters (and relative, for ratios): limits met within rounding
constexpr double kMinClearance = 0.01;  // meters between two openings of a panel, whatever min_gap says
constexpr int kMaxSweeps = 16;          // over all edges, per step size

// Element squares [first, last] along one axis overlapped by the interval (a, b) of the grid.
std::pair<int, int> cells(double a, double b, double s) {
  return {static_cast<int>(std::floor(a / s + kTolerance)), static_cast<int>(std::ceil(b / s - kTolerance)) - 1};
}

bool covers_elements(const Panel& panel, double u0, double u1, double v0, double v1, double s) {
  const auto [c0, c1] = cells(u0, u1, s);
  const auto [r0, r1] = cells(v0, v1, s);
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c)
      if (r < 0 || c < 0 || r >= panel.rows || c >= panel.cols || panel.grid[static_cast<size_t>(r) * panel.cols + c] < 0)
        return false;
  return true;
}

std::string meters(double x) {
  std::ostringstream s;
  s << x << " m";
  return s.str();
}

// The elements whose squares overlap the strip between two positions of one edge of `r`.
std::vector<int> strip_elements(const Panel& panel, const PanelRectangle& r, int edge, double from, double to,
                                double s) {
  double u0 = r.u0, u1 = r.u1, v0 = r.v0, v1 = r.v1;
  const double lo = std::min(from, to), hi = std::max(from, to);
  if (edge < 2) u0 = lo, u1 = hi;
  else v0 = lo, v1 = hi;
  std::vector<int> out;
  const auto [c0, c1] = cells(u0, u1, s);
  const auto [r0, r1] = cells(v0, v1, s);
  for (int row = std::max(0, r0 - 1); row <= std::min(panel.rows - 1, r1 + 1); ++row)
    for (int col = std::max(0, c0 - 1); col <= std::min(panel.cols - 1, c1 + 1); ++col) {
      const int k = panel.grid[static_cast<size_t>(row) * panel.cols + col];
      if (k >= 0) out.push_back(k);
    }
  return out;
}

double& edge_of(PanelRectangle& r, int edge) {
  switch (edge) {
    case 0: return r.u0;
    case 1: return r.u1;
    case 2: return r.v0;
    default: return r.v1;
  }
}

double snap(double x, double module) { return module > 0.0 ? module * std::round(x / module) : x; }

}  // namespace

PanelRectangle panel_rectangle(const GridRectangle& r, double s) {
  return {r.panel, r.col0 * s, (r.col1 + 1) * s, r.row0 * s, (r.row1 + 1) * s};
}

bool admissible(const PanelRectangle& r, const Panel& panel, const OpeningConstraints& all, double s,
                std::string* why) {
  const OpeningConstraints& c = all.for_panel(r.panel);
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  const double w = r.width(), h = r.height();
  if (!(w > kContinuousEdgeStep - kTolerance && h > kContinuousEdgeStep - kTolerance))
    return fail("is narrower than " + meters(kContinuousEdgeStep));
  if (!covers_elements(panel, r.u0, r.u1, r.v0, r.v1, s)) return fail("leaves the panel's elements");
  const double m = c.margin;
  if (m > 0.0 && !covers_elements(panel, r.u0 - m, r.u1 + m, r.v0 - m, r.v1 + m, s))
    return fail("lies closer than margin " + meters(m) + " to the panel's edge");
  if (w < c.min_width - kTolerance || w > c.max_width + kTolerance) return fail("has width " + meters(w) + " out of its limits");
  if (h < c.min_height - kTolerance || h > c.max_height + kTolerance)
    return fail("has height " + meters(h) + " out of its limits");
  if (w * h < c.min_area * (1 - kTolerance) || w * h > c.max_area * (1 + kTolerance)) return fail("has an area out of its limits");
  if (w / h < c.min_aspect * (1 - kTolerance) || w / h > c.max_aspect * (1 + kTolerance))
    return fail("has an aspect ratio out of its limits");
  if (is_wall(panel)) {
    const std::vector<double>& base_z = all.panel_base_z;
    const double grid_bottom = panel.origin.z() + std::min(0.0, panel.rows * s * static_cast<double>(panel.v_axis.z()));
    const double base = base_z.empty() ? grid_bottom : base_z[static_cast<size_t>(r.panel)];
    const double z0 = panel.origin.z() + r.v0 * panel.v_axis.z(), z1 = panel.origin.z() + r.v1 * panel.v_axis.z();
    const double sill = std::min(z0, z1) - base, head = std::max(z0, z1) - base;
    if (sill < c.sill_min - kTolerance || sill > c.sill_max + kTolerance) return fail("has its sill out of its limits");
    if (head < c.head_min - kTolerance || head > c.head_max + kTolerance) return fail("has its head out of its limits");
  }
  return true;
}

bool apart(const PanelRectangle& a, const PanelRectangle& b, const OpeningConstraints& c) {
  if (a.panel != b.panel) return true;
  const double gap_u = std::max({0.0, b.u0 - a.u1, a.u0 - b.u1}), gap_v = std::max({0.0, b.v0 - a.v1, a.v0 - b.v1});
  const double d = std::hypot(gap_u, gap_v);
  return d >= std::max(kMinClearance, c.for_panel(a.panel).min_gap) - kTolerance;
}

EdgeRefinement refine_edges(const OpeningDomain& domain, const Contributions& c, const LinearObjective& objective,
                            const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                            Progress* progress) {
  const double s = domain.element_size();
  EdgeRefinement out;
  RegionSearch search(c, domain, start);
  const Eigen::VectorXd closed = c.closed.value;
  double error = prediction_error(objective, search.values() - closed);
  const double module = constraints.module;
  const double smallest = module > 0.0 ? module : kContinuousEdgeStep;
  // Whole elements first (every panel), then halving steps (zero-thickness panels only).
  std::vector<double> steps = {s};
  for (double step = 0.5 * s; step >= smallest * (1.0 - 1e-9);) {
    const double snapped = module > 0.0 ? std::max(module, snap(step, module)) : step;
    if (snapped < steps.back() * (1.0 - 1e-9)) steps.push_back(snapped);
    if (module > 0.0 && snapped <= module * (1.0 + 1e-9)) break;
    step = 0.5 * snapped;
  }
  for (const double step : steps) {
    const bool whole_elements = step >= s * (1.0 - 1e-9);
    bool moved = true;
    for (int sweep = 0; moved && sweep < kMaxSweeps; ++sweep) {
      moved = false;
      for (size_t i = 0; i < search.rectangles().size(); ++i) {
        const PanelRectangle& current = search.rectangles()[i];
        const Panel& panel = domain.panels()[current.panel];
        if (panel.thickness > 0.0f && !whole_elements) continue;  // the tubes of a thick wall follow the grid
        // One edge at a time, or two opposite edges together (the opening slides along u or v).
        static constexpr std::array<std::array<int, 2>, 6> kMoves = {
            {{0, -1}, {1, -1}, {2, -1}, {3, -1}, {0, 1}, {2, 3}}};
        for (const auto& move : kMoves)
          for (double direction : {-1.0, 1.0}) {
            if (progress) progress->throw_if_cancelled();
            std::vector<PanelRectangle> candidate = search.rectangles();
            PanelRectangle& r = candidate[i];
            std::vector<int> touched;
            bool changed = true;
            for (int edge : move) {
              if (edge < 0) continue;
              const double from = edge_of(r, edge);
              edge_of(r, edge) = whole_elements ? from + direction * step : snap(from + direction * step, module);
              changed = changed && edge_of(r, edge) != from;
              const std::vector<int> strip = strip_elements(panel, r, edge, from, edge_of(r, edge), s);
              touched.insert(touched.end(), strip.begin(), strip.end());
            }
            if (!changed || !admissible(r, panel, constraints, s)) continue;
            bool clear = true;
            for (size_t j = 0; j < candidate.size() && clear; ++j)
              if (j != i) clear = apart(r, candidate[j], constraints);
            if (!clear) continue;
            const Eigen::VectorXd& values = search.try_region(candidate, touched);
            ++out.evaluations;
            const double e = prediction_error(objective, values - closed);
            if (e < error * (1.0 - 1e-9)) {
              search.accept();
              error = e;
              ++out.moves;
              moved = true;
            }
          }
      }
    }
  }
  out.openings = search.rectangles();
  return out;
}

}  // namespace fenestra
