#include "scene/opening_constraints.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Element sizes are single precision: a whole number of elements may miss a limit in the
// seventh digit, which must not count as missing it.
constexpr double kRelative = 1e-6;
// Heights come from single-precision world coordinates.
constexpr double kHeightTolerance = 1e-5;  // meters
constexpr double kMaxModule = 10.0;         // meters: a module for openings' edges
constexpr int kMaxCount = 1 << 30;         // "unlimited" rows or columns
constexpr int64_t kMaxElements = int64_t{1} << 60;
// Feasibility is searched over widths up to this many elements; no domain comes close.
constexpr int kMaxSearchedWidth = 1 << 22;

const char* kKey = "solver.constraints: ";

// Smallest whole number not below x, and largest not above it (x >= 0), forgiving rounding.
int64_t count_at_least(double x) {
  return static_cast<int64_t>(std::ceil(x * (1.0 - kRelative) - kRelative));
}
int64_t count_at_most(double x, int64_t unlimited) {
  if (!std::isfinite(x) || x >= static_cast<double>(unlimited)) return unlimited;
  return static_cast<int64_t>(std::floor(x * (1.0 + kRelative) + kRelative));
}

std::string number(double x) { return std::isinf(x) ? "unlimited" : decimal_text(x); }
std::string meters(double x) { return number(x) + (std::isinf(x) ? "" : " m"); }
std::string square_meters(double x) { return number(x) + (std::isinf(x) ? "" : " m^2"); }

[[noreturn]] void refuse(const std::string& message) { throw std::invalid_argument(kKey + message); }

void check_value(const char* name, double value, bool may_be_unlimited) {
  if (std::isnan(value)) refuse(std::string(name) + " is not a number");
  if (value < 0.0) refuse(std::string(name) + " " + number(value) + " is negative");
  if (!may_be_unlimited && std::isinf(value)) refuse(std::string(name) + " must be finite");
}

void check_range(const char* min_name, double min, const char* max_name, double max,
                 std::string (*unit)(double)) {
  if (min > max) refuse(std::string(min_name) + " " + unit(min) + " > " + max_name + " " + unit(max));
}

// Sizes and heads must leave room (a sill may be 0: a door or a floor-level window).
void check_room(const char* name, double max) {
  if (max == 0.0) refuse(std::string(name) + " 0 leaves no room for any opening");
}

// Wall openings: head = sill + height on a vertical wall, so some height must bridge the
// sill and head limits.
void check_heights(const OpeningConstraints& c, const GridLimits& g, double a) {
  if (c.sill_min > c.head_max)
    refuse("sill_min " + meters(c.sill_min) + " is above head_max " + meters(c.head_max));
  if (c.sill_min + c.min_height > c.head_max * (1.0 + kRelative))
    refuse("sill_min " + meters(c.sill_min) + " + min_height " + meters(c.min_height) + " > head_max " +
           meters(c.head_max));
  if (c.sill_max + c.max_height < c.head_min * (1.0 - kRelative))
    refuse("sill_max " + meters(c.sill_max) + " + max_height " + meters(c.max_height) + " < head_min " +
           meters(c.head_min));
  const int64_t lo = std::max<int64_t>(g.min_rows, count_at_least(std::max(0.0, c.head_min - c.sill_max) / a));
  const int64_t hi = std::min<int64_t>(g.max_rows, count_at_most((c.head_max - c.sill_min) / a, kMaxCount));
  if (lo > hi)
    refuse("no height that is a multiple of the element size " + meters(a) + " and within min_height " +
           meters(c.min_height) + " .. max_height " + meters(c.max_height) + " reaches from a sill in " +
           meters(c.sill_min) + " .. " + meters(c.sill_max) + " to a head in " + meters(c.head_min) + " .. " +
           meters(c.head_max) + " (on a vertical wall)");
}

// Whether some whole number of columns and rows meets size, area and aspect together.
bool some_size_fits(const GridLimits& g) {
  const int64_t last = std::min<int64_t>(g.max_cols, int64_t{g.min_cols} + kMaxSearchedWidth);
  for (int64_t cols = g.min_cols; cols <= last && cols * g.min_rows <= g.max_elements; ++cols) {
    int64_t lo = std::max<int64_t>(g.min_rows, (g.min_elements + cols - 1) / cols);
    int64_t hi = std::min<int64_t>(g.max_rows, g.max_elements / cols);
    if (g.max_aspect < kInfinity) lo = std::max(lo, count_at_least(static_cast<double>(cols) / g.max_aspect));
    if (g.min_aspect > 0.0) hi = std::min(hi, count_at_most(static_cast<double>(cols) / g.min_aspect, kMaxCount));
    if (lo > hi) continue;
    for (int64_t rows = lo; rows <= std::min(hi, lo + 2); ++rows)  // rounding at the ends
      if (g.fits(static_cast<int>(rows), static_cast<int>(cols))) return true;
  }
  return false;
}

// Extents of a panel's grid along u and v (m): its last grid lines (multiples of the element
// size).
double grid_extent(const std::vector<float>& lines, int cells, double a) {
  return lines.empty() ? cells * a : static_cast<double>(lines.back());
}
double grid_bottom_z(const Panel& panel, double a) {
  const double z0 = panel.origin.z();
  const double rise_v = grid_extent(panel.v_lines, panel.rows, a) * panel.v_axis.z();
  const double rise_u = grid_extent(panel.u_lines, panel.cols, a) * panel.u_axis.z();
  return z0 + std::min(0.0, rise_v) + std::min(0.0, rise_u);
}
double grid_top_z(const Panel& panel, double a) {
  const double z0 = panel.origin.z();
  const double rise_v = grid_extent(panel.v_lines, panel.rows, a) * panel.v_axis.z();
  const double rise_u = grid_extent(panel.u_lines, panel.cols, a) * panel.u_axis.z();
  return z0 + std::max(0.0, rise_v) + std::max(0.0, rise_u);
}

// An explanation of why a rows x cols opening does not fit (empty when it does).
bool size_fits(int rows, int cols, const GridLimits& g) {
  const int64_t n = int64_t{rows} * cols;
  return cols >= g.min_cols && cols <= g.max_cols && rows >= g.min_rows && rows <= g.max_rows &&
         n >= g.min_elements && n <= g.max_elements && g.fits(rows, cols);
}

// Why a size does not fit (size_fits false), in the user's words.
std::string size_problem(int rows, int cols, const OpeningConstraints& c, const GridLimits& g, double a) {
  const double width = cols * a, height = rows * a;
  std::ostringstream s;
  s << "is " << width << " m wide and " << height << " m high";
  if (cols < g.min_cols) return s.str() + ", narrower than min_width " + meters(c.min_width);
  if (cols > g.max_cols) return s.str() + ", wider than max_width " + meters(c.max_width);
  if (rows < g.min_rows) return s.str() + ", lower than min_height " + meters(c.min_height);
  if (rows > g.max_rows) return s.str() + ", higher than max_height " + meters(c.max_height);
  const int64_t n = int64_t{rows} * cols;
  if (n < g.min_elements) return s.str() + ", smaller than min_area " + square_meters(c.min_area);
  if (n > g.max_elements) return s.str() + ", larger than max_area " + square_meters(c.max_area);
  if (!g.fits(rows, cols))
    return s.str() + " (aspect " + number(width / height) + "), outside min_aspect " + number(c.min_aspect) +
           " .. max_aspect " + number(c.max_aspect);
  return {};
}

}  // namespace

bool OpeningConstraints::any() const {
  return min_area > 0.0 || max_area < kInfinity || min_aspect > 0.0 || max_aspect < kInfinity ||
         min_width > 0.0 || max_width < kInfinity || min_height > 0.0 || max_height < kInfinity ||
         max_openings > 0 || min_gap > 0.0 || margin > 0.0 || sill_min > 0.0 || sill_max < kInfinity ||
         head_min > 0.0 || head_max < kInfinity || head_clearance > 0.0 || max_openings_per_panel > 0 ||
         panel_width_per_opening > 0.0 || !catalogue.empty() || composes();
}

std::vector<AutomaticConstraint> automatic_constraints(bool full_height, bool climate) {
  std::vector<AutomaticConstraint> list = {
      {"min_width", 0.5, "openings at least 0.5 m wide"},
      {"min_height", 0.5, "openings at least 0.5 m high"},
      {"min_gap", 0.5, "a pier of at least 0.5 m between two openings"},
      {"panel_width_per_opening", 3.0, "at most one opening per 3 m of a panel's width"},
  };
  if (climate) list.push_back({"min_area", kClimateMinArea, "with climate goals, openings of at least 1 m2"});
  if (!full_height) {
    list.push_back({"margin", 0.2, "0.2 m clear of a panel's edges and corners"});
    list.push_back({"sill_min", 0.3, "sills at least 0.3 m above a wall's bottom"});
    list.push_back({"head_clearance", 0.2, "heads at least 0.2 m below a wall's top"});
  }
  return list;
}

void set_constraint(OpeningConstraints* c, const std::string& key, double value) {
  const std::pair<const char*, double*> keys[] = {
      {"min_width", &c->min_width}, {"min_height", &c->min_height},
      {"min_gap", &c->min_gap},     {"panel_width_per_opening", &c->panel_width_per_opening},
      {"margin", &c->margin},       {"sill_min", &c->sill_min},
      {"head_clearance", &c->head_clearance}, {"min_area", &c->min_area}};
  for (const auto& [name, field] : keys)
    if (key == name) {
      *field = value;
      return;
    }
  throw std::invalid_argument("opening constraints: no automatic key '" + key + "'");
}

std::string OpeningConstraints::to_string() const {
  std::ostringstream s;
  s << "OpeningConstraints(";
  const char* sep = "";
  auto item = [&](const char* name, double value, double unset, const char* unit) {
    if (value == unset) return;
    s << sep << name << "=" << number(value) << (std::isinf(value) ? "" : unit);
    sep = ", ";
  };
  item("min_area", min_area, 0.0, " m^2");
  item("max_area", max_area, kInfinity, " m^2");
  item("min_aspect", min_aspect, 0.0, "");
  item("max_aspect", max_aspect, kInfinity, "");
  item("min_width", min_width, 0.0, " m");
  item("max_width", max_width, kInfinity, " m");
  item("min_height", min_height, 0.0, " m");
  item("max_height", max_height, kInfinity, " m");
  item("max_openings", max_openings, 0, "");
  item("min_gap", min_gap, 0.0, " m");
  item("margin", margin, 0.0, " m");
  item("module", module, 0.0, " m");
  item("sill_min", sill_min, 0.0, " m");
  item("sill_max", sill_max, kInfinity, " m");
  item("head_min", head_min, 0.0, " m");
  item("head_max", head_max, kInfinity, " m");
  item("head_clearance", head_clearance, 0.0, " m");
  item("max_openings_per_panel", max_openings_per_panel, 0, "");
  item("panel_width_per_opening", panel_width_per_opening, 0.0, " m");
  if (!catalogue.empty()) s << sep << "catalogue=" << catalogue.name, sep = ", ";
  if (!any()) s << "unconstrained";
  s << ")";
  return s.str();
}

bool GridRectangle::operator<(const GridRectangle& o) const {
  return std::tie(panel, row0, col0, row1, col1) < std::tie(o.panel, o.row0, o.col0, o.row1, o.col1);
}

std::string GridRectangle::to_string() const {
  std::ostringstream s;
  s << "opening on panel " << panel << ", rows " << row0 << "-" << row1 << ", columns " << col0 << "-" << col1;
  return s.str();
}

bool GridLimits::fits(int rows, int cols) const {
  if (rows < min_rows || rows > max_rows || cols < min_cols || cols > max_cols) return false;
  const int64_t n = int64_t{rows} * cols;
  if (n < min_elements || n > max_elements) return false;
  return cols >= min_aspect * rows * (1.0 - kRelative) && cols <= max_aspect * rows * (1.0 + kRelative);
}

GridLimits grid_limits(const OpeningConstraints& c, double a) {
  GridLimits g;
  g.min_cols = static_cast<int>(std::max<int64_t>(1, count_at_least(c.min_width / a)));
  g.max_cols = static_cast<int>(count_at_most(c.max_width / a, kMaxCount));
  g.min_rows = static_cast<int>(std::max<int64_t>(1, count_at_least(c.min_height / a)));
  g.max_rows = static_cast<int>(count_at_most(c.max_height / a, kMaxCount));
  g.min_elements = std::max<int64_t>(1, count_at_least(c.min_area / (a * a)));
  g.max_elements = count_at_most(c.max_area / (a * a), kMaxElements);
  g.min_aspect = c.min_aspect;
  g.max_aspect = c.max_aspect;
  g.margin_elements = static_cast<int>(std::max<int64_t>(0, count_at_least(c.margin / a)));
  g.gap_elements = static_cast<int>(std::max<int64_t>(1, count_at_least(c.min_gap / a)));
  return g;
}

void check_feasible(const OpeningConstraints& c, double a) {
  if (!(a > 0.0) || !std::isfinite(a)) refuse("the element size " + number(a) + " must be a positive length");
  check_value("min_area", c.min_area, false);
  check_value("max_area", c.max_area, true);
  check_value("min_aspect", c.min_aspect, false);
  check_value("max_aspect", c.max_aspect, true);
  check_value("min_width", c.min_width, false);
  check_value("max_width", c.max_width, true);
  check_value("min_height", c.min_height, false);
  check_value("max_height", c.max_height, true);
  check_value("min_gap", c.min_gap, false);
  check_value("margin", c.margin, false);
  check_value("module", c.module, false);
  if (c.module > kMaxModule) refuse("module " + meters(c.module) + " is larger than " + meters(kMaxModule));
  check_value("sill_min", c.sill_min, false);
  check_value("sill_max", c.sill_max, true);
  check_value("head_min", c.head_min, false);
  check_value("head_max", c.head_max, true);
  check_value("head_clearance", c.head_clearance, false);
  check_value("panel_width_per_opening", c.panel_width_per_opening, false);
  if (c.max_openings_per_panel < 0)
    refuse("max_openings_per_panel " + std::to_string(c.max_openings_per_panel) + " is negative");
  if (c.max_openings < 0) refuse("max_openings " + std::to_string(c.max_openings) + " is negative");
  for (size_t i = 0; i < c.panel_base_z.size(); ++i)
    if (!std::isfinite(c.panel_base_z[i])) refuse("the base height of panel " + std::to_string(i) + " is not finite");
  for (size_t i = 0; i < c.panel_top_z.size(); ++i)
    if (!std::isfinite(c.panel_top_z[i])) refuse("the top height of panel " + std::to_string(i) + " is not finite");

  check_range("min_area", c.min_area, "max_area", c.max_area, square_meters);
  check_range("min_aspect", c.min_aspect, "max_aspect", c.max_aspect, number);
  check_range("min_width", c.min_width, "max_width", c.max_width, meters);
  check_range("min_height", c.min_height, "max_height", c.max_height, meters);
  check_range("sill_min", c.sill_min, "sill_max", c.sill_max, meters);
  check_range("head_min", c.head_min, "head_max", c.head_max, meters);
  check_room("max_area", c.max_area);
  check_room("max_aspect", c.max_aspect);
  check_room("max_width", c.max_width);
  check_room("max_height", c.max_height);
  check_room("head_max", c.head_max);

  // Pairs of limits that contradict each other whatever the grid.
  if (c.min_width * c.min_height > c.max_area * (1.0 + kRelative))
    refuse("min_width " + meters(c.min_width) + " x min_height " + meters(c.min_height) + " = " +
           square_meters(c.min_width * c.min_height) + " > max_area " + square_meters(c.max_area));
  if (c.max_width * c.max_height < c.min_area * (1.0 - kRelative))
    refuse("max_width " + meters(c.max_width) + " x max_height " + meters(c.max_height) + " = " +
           square_meters(c.max_width * c.max_height) + " < min_area " + square_meters(c.min_area));
  if (c.min_height > 0.0 && c.max_width / c.min_height < c.min_aspect * (1.0 - kRelative))
    refuse("max_width " + meters(c.max_width) + " / min_height " + meters(c.min_height) + " = " +
           number(c.max_width / c.min_height) + " < min_aspect " + number(c.min_aspect));
  if (c.min_width > 0.0 && c.min_width / c.max_height > c.max_aspect * (1.0 + kRelative))
    refuse("min_width " + meters(c.min_width) + " / max_height " + meters(c.max_height) + " = " +
           number(c.min_width / c.max_height) + " > max_aspect " + number(c.max_aspect));

  // Sides are whole numbers of elements.
  const GridLimits g = grid_limits(c, a);
  if (g.min_cols > g.max_cols)
    refuse("no multiple of the element size " + meters(a) + " lies within min_width " + meters(c.min_width) +
           " .. max_width " + meters(c.max_width));
  if (g.min_rows > g.max_rows)
    refuse("no multiple of the element size " + meters(a) + " lies within min_height " + meters(c.min_height) +
           " .. max_height " + meters(c.max_height));
  if (g.min_elements > g.max_elements)
    refuse("no whole number of elements of " + square_meters(a * a) + " lies within min_area " +
           square_meters(c.min_area) + " .. max_area " + square_meters(c.max_area));
  if (!some_size_fits(g))
    refuse("no opening with sides multiple of the element size " + meters(a) + " meets width " +
           meters(c.min_width) + " .. " + meters(c.max_width) + ", height " + meters(c.min_height) + " .. " +
           meters(c.max_height) + ", area " + square_meters(c.min_area) + " .. " + square_meters(c.max_area) +
           " and aspect " + number(c.min_aspect) + " .. " + number(c.max_aspect) + " together");
  for (size_t i = 0; i < c.sill_heights.size(); ++i) {
    const double h = c.sill_heights[i];
    const std::string name = "sill_heights[" + std::to_string(i) + "] " + meters(h);
    if (h < c.sill_min - kHeightTolerance) refuse(name + " is below sill_min " + meters(c.sill_min));
    if (h > c.sill_max + kHeightTolerance) refuse(name + " is above sill_max " + meters(c.sill_max));
    if (h + c.min_height > c.head_max + kHeightTolerance)
      refuse(name + " + min_height " + meters(c.min_height) + " is above head_max " + meters(c.head_max));
  }
  const bool heights = c.sill_min > 0.0 || c.sill_max < kInfinity || c.head_min > 0.0 || c.head_max < kInfinity;
  if (heights) check_heights(c, g, a);
}

PanelHeights wall_heights(const Panel& panel, int panel_index, const OpeningConstraints& all, double a) {
  const std::vector<double>& base_z = all.panel_base_z;
  if (!base_z.empty() && panel_index >= static_cast<int>(base_z.size()))
    throw std::invalid_argument("opening constraints: panel_base_z has " + std::to_string(base_z.size()) +
                                " values, panel " + std::to_string(panel_index) + " has none");
  const std::vector<double>& top_z = all.panel_top_z;
  PanelHeights h;
  h.base = base_z.empty() ? grid_bottom_z(panel, a) : base_z[panel_index];
  h.top = panel_index < static_cast<int>(top_z.size()) ? top_z[panel_index] : grid_top_z(panel, a);
  return h;
}

RowHeights row_heights(const Panel& panel, int row0, int row1, const PanelHeights& wall, double a) {
  const double z0 = panel.origin.z() + row0 * a * panel.v_axis.z();
  const double z1 = panel.origin.z() + (row1 + 1) * a * panel.v_axis.z();
  return {std::min(z0, z1) - wall.base, std::max(z0, z1) - wall.base};
}

bool heights_ok(const Panel& panel, int panel_index, int row0, int row1, const OpeningConstraints& all, double a,
                std::string* why) {
  if (!is_wall(panel)) return true;
  const OpeningConstraints& c = all.for_panel(panel_index);
  const PanelHeights wall = wall_heights(panel, panel_index, all, a);
  const double base = wall.base, top = wall.top;
  const RowHeights rows = row_heights(panel, row0, row1, wall, a);
  const double sill = rows.sill, head = rows.head;
  auto fail = [&](const auto& what) {
    if (why) *why = what();
    return false;
  };
  auto at_sill = [&] { return "has its sill at " + meters(sill); };
  auto at_head = [&] { return "has its head at " + meters(head); };
  if (sill < c.sill_min - kHeightTolerance) return fail([&] { return at_sill() + ", below sill_min " + meters(c.sill_min); });
  if (sill > c.sill_max + kHeightTolerance) return fail([&] { return at_sill() + ", above sill_max " + meters(c.sill_max); });
  if (head < c.head_min - kHeightTolerance) return fail([&] { return at_head() + ", below head_min " + meters(c.head_min); });
  if (head > c.head_max + kHeightTolerance) return fail([&] { return at_head() + ", above head_max " + meters(c.head_max); });
  if (head > top - base - c.head_clearance + kHeightTolerance)
    return fail([&] {
      return at_head() + ", less than head_clearance " + meters(c.head_clearance) + " below the wall's top at " +
             meters(top - base);
    });
  return true;
}

std::vector<double> panel_base_heights(const OpeningDomain& domain, const Mesh& mesh) {
  std::vector<double> base;
  for (const Panel& panel : domain.panels()) {
    double z = kInfinity;
    for (uint32_t t : panel.triangles)
      for (int k = 0; k < 3; ++k) z = std::min(z, static_cast<double>(mesh.vertex(t, k).z()));
    base.push_back(z);
  }
  return base;
}

std::vector<double> panel_top_heights(const OpeningDomain& domain, const Mesh& mesh) {
  std::vector<double> top;
  for (const Panel& panel : domain.panels()) {
    double z = -kInfinity;
    for (uint32_t t : panel.triangles)
      for (int k = 0; k < 3; ++k) z = std::max(z, static_cast<double>(mesh.vertex(t, k).z()));
    top.push_back(z);
  }
  return top;
}

std::vector<uint8_t> elements_out_of_bounds(const OpeningDomain& domain, const OpeningConstraints& all) {
  const double a = domain.element_size();
  std::vector<uint8_t> out(domain.element_count(), 0);
  for (size_t p = 0; p < domain.panels().size(); ++p) {
    const Panel& panel = domain.panels()[p];
    const int index = static_cast<int>(p);
    const OpeningConstraints& c = all.for_panel(index);
    const int m = grid_limits(c, a).margin_elements;
    auto exists = [&](int row, int col) {
      return row >= 0 && col >= 0 && row < panel.rows && col < panel.cols &&
             panel.grid[static_cast<size_t>(row) * panel.cols + col] >= 0;
    };
    const PanelHeights wall = wall_heights(panel, index, all, a);
    const double highest_head = std::min(c.head_max, wall.top - wall.base - c.head_clearance);
    for (int row = 0; row < panel.rows; ++row) {
      const RowHeights h = row_heights(panel, row, row, wall, a);
      const bool out_of_heights = is_wall(panel) && (h.sill < c.sill_min - kHeightTolerance ||
                                                     h.head > highest_head + kHeightTolerance);
      for (int col = 0; col < panel.cols; ++col) {
        const int k = panel.grid[static_cast<size_t>(row) * panel.cols + col];
        if (k < 0) continue;
        bool clear = !out_of_heights;
        for (int r = row - m; r <= row + m && clear; ++r)
          for (int q = col - m; q <= col + m && clear; ++q) clear = exists(r, q);
        out[static_cast<size_t>(k)] = clear ? 0 : 1;
      }
    }
  }
  return out;
}

int panel_opening_limit(const Panel& panel, int panel_index, const OpeningConstraints& all, double a) {
  const OpeningConstraints& c = all.for_panel(panel_index);
  int limit = c.max_openings_per_panel;
  const double w = c.panel_width_per_opening;
  if (w > 0.0) {
    auto per_side = [&](int elements) {
      return static_cast<int>(std::min<double>(kMaxCount, std::max(1.0, std::ceil(elements * a / w - kRelative))));
    };
    const int64_t n = int64_t{per_side(panel.cols)} * (is_wall(panel) ? 1 : per_side(panel.rows));
    const int by_size = static_cast<int>(std::min<int64_t>(n, kMaxCount));
    limit = limit > 0 ? std::min(limit, by_size) : by_size;
  }
  return limit;
}

bool satisfies(const GridRectangle& r, const Panel& panel, const OpeningConstraints& all, double a,
               std::string* why) {
  const OpeningConstraints& c = all.for_panel(r.panel);
  auto fail = [&](const std::string& what) {
    if (why) *why = r.to_string() + " " + what;
    return false;
  };
  if (r.row0 < 0 || r.col0 < 0 || r.row0 > r.row1 || r.col0 > r.col1 || r.row1 >= panel.rows || r.col1 >= panel.cols)
    return fail("is not within the panel's grid of " + std::to_string(panel.rows) + " rows and " +
                std::to_string(panel.cols) + " columns");
  auto exists = [&](int row, int col) {
    return row >= 0 && col >= 0 && row < panel.rows && col < panel.cols &&
           panel.grid[static_cast<size_t>(row) * panel.cols + col] >= 0;
  };
  for (int row = r.row0; row <= r.row1; ++row)
    for (int col = r.col0; col <= r.col1; ++col)
      if (!exists(row, col)) return fail("covers a square that leaves the panel");
  const GridLimits g = grid_limits(c, a);
  const int m = g.margin_elements;
  for (int row = r.row0 - m; row <= r.row1 + m; ++row)
    for (int col = r.col0 - m; col <= r.col1 + m; ++col)
      if (!exists(row, col)) return fail("lies closer than margin " + meters(c.margin) + " to the panel's edge");
  // Reasons are worded only when asked for: the searches check millions of rectangles.
  if (!size_fits(r.rows(), r.cols(), g)) return fail(size_problem(r.rows(), r.cols(), c, g, a));
  std::string heights;
  if (!heights_ok(panel, r.panel, r.row0, r.row1, all, a, why ? &heights : nullptr)) return fail(heights);
  return true;
}

double clear_distance(const GridRectangle& a, const GridRectangle& b, double element_size) {
  if (a.panel != b.panel) return kInfinity;
  const int gap_cols = std::max({0, b.col0 - a.col1 - 1, a.col0 - b.col1 - 1});
  const int gap_rows = std::max({0, b.row0 - a.row1 - 1, a.row0 - b.row1 - 1});
  return element_size * std::hypot(static_cast<double>(gap_cols), static_cast<double>(gap_rows));
}

bool apart(const GridRectangle& a, const GridRectangle& b, const OpeningConstraints& c, double element_size) {
  if (a.panel != b.panel) return true;
  // Separate regions: no shared or N-8 adjacent elements, i.e. at least one element between.
  const double d = clear_distance(a, b, element_size);
  return d >= element_size * (1.0 - kRelative) && d >= c.for_panel(a.panel).min_gap * (1.0 - kRelative);
}

bool satisfies_all(const OpeningDomain& domain, const std::vector<GridRectangle>& rects,
                   const OpeningConstraints& c, std::string* why) {
  const double a = domain.element_size();
  const int panels = static_cast<int>(domain.panels().size());
  if (!c.panel_base_z.empty() && static_cast<int>(c.panel_base_z.size()) != panels)
    throw std::invalid_argument("opening constraints: panel_base_z has " + std::to_string(c.panel_base_z.size()) +
                                " values for " + std::to_string(panels) + " panels");
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  if (c.max_openings > 0 && static_cast<int>(rects.size()) > c.max_openings)
    return fail(std::to_string(rects.size()) + " openings, more than max_openings " + std::to_string(c.max_openings));
  std::vector<int> per_panel(static_cast<size_t>(panels), 0);
  for (const GridRectangle& r : rects) {
    if (r.panel < 0 || r.panel >= panels) return fail(r.to_string() + " names no panel of the domain");
    if (!satisfies(r, domain.panels()[r.panel], c, a, why)) return false;
    const int limit = panel_opening_limit(domain.panels()[r.panel], r.panel, c, a);
    if (limit > 0 && ++per_panel[r.panel] > limit)
      return fail("panel " + std::to_string(r.panel) + " has more than " + std::to_string(limit) +
                  " openings (max_openings_per_panel, panel_width_per_opening)");
  }
  for (size_t i = 0; i < rects.size(); ++i)
    for (size_t j = i + 1; j < rects.size(); ++j)
      if (!apart(rects[i], rects[j], c, a)) {
        const double d = clear_distance(rects[i], rects[j], a);
        return fail(rects[i].to_string() + " and " + rects[j].to_string() + " are " + meters(d) +
                    " apart: they must be separate (one element) and at least min_gap " +
                    meters(c.for_panel(rects[i].panel).min_gap) +
                    " apart");
      }
  return true;
}

std::vector<uint8_t> rectangles_mask(const OpeningDomain& domain, const std::vector<GridRectangle>& rects) {
  std::vector<uint8_t> open(domain.element_count(), 0);
  for (const GridRectangle& r : rects) {
    if (r.panel < 0 || r.panel >= static_cast<int>(domain.panels().size()))
      throw std::invalid_argument(r.to_string() + " names no panel of the domain");
    const Panel& panel = domain.panels()[r.panel];
    if (r.row0 < 0 || r.col0 < 0 || r.row1 >= panel.rows || r.col1 >= panel.cols)
      throw std::invalid_argument(r.to_string() + " is not within its panel's grid");
    for (int row = r.row0; row <= r.row1; ++row)
      for (int col = r.col0; col <= r.col1; ++col) {
        const int k = panel.grid[static_cast<size_t>(row) * panel.cols + col];
        if (k >= 0) open[k] = 1;
      }
  }
  return open;
}

std::string catalogue_fit_problem(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  const double a = domain.element_size();
  double room_w = 0.0, room_h = 0.0, size_w = 0.0, size_h = 0.0;
  bool any = false;
  for (size_t p = 0; p < domain.panels().size(); ++p) {
    const Panel& panel = domain.panels()[p];
    const OpeningConstraints& set = constraints.for_panel(static_cast<int>(p));
    const std::vector<CatalogueSize> sizes = set.catalogue.sizes_for(panel);
    if (sizes.empty()) continue;
    const double margin = a * std::ceil(set.margin / a - 1e-6);
    const double w = panel.cols * a - 2.0 * margin;
    double h = panel.rows * a - 2.0 * margin;
    if (is_wall(panel)) h = std::min(h, panel.rows * a - set.sill_min - set.head_clearance);
    for (const CatalogueSize& size : sizes)
      if (size.width <= w + 1e-6 && size.height <= h + 1e-6) return {};
    if (!any || w * h > room_w * room_h) room_w = w, room_h = h;
    for (const CatalogueSize& size : sizes)
      if (!any || size.width * size.height < size_w * size_h) size_w = size.width, size_h = size.height, any = true;
  }
  if (!any) return {};
  char text[256];
  std::snprintf(text, sizeof text,
                "no size fits any panel: the largest room for an opening is %.2f x %.2f m (panel less margin, "
                "sill_min and head_clearance), the smallest size %.2f x %.2f m",
                std::max(0.0, room_w), std::max(0.0, room_h), size_w, size_h);
  return text;
}

std::string composition_problem(const OpeningDomain& domain, const OpeningConstraints& constraints) {
  const std::vector<int> facade = facades_of(domain);
  for (size_t p = 0; p < facade.size(); ++p)
    if (constraints.for_panel(static_cast<int>(p)).composes_by_choice() && facade[p] >= 0) return {};
  for (size_t p = 0; p < facade.size(); ++p)
    if (constraints.for_panel(static_cast<int>(p)).composes_by_choice())
      return "align_sills, align_heads, equal_widths, same_type_in_row, symmetric, equal_spacing and sill_heights "
             "apply to flat walls, and the opening domain has none where they are set";
  return {};
}

}  // namespace fenestra
