#pragma once
// What makes an opening architecturally admissible (the paper's shape constraints): a rectangle
// of whole elements within one panel, with limits on its size, proportions, placement and count.
//
// Width runs along the panel's u axis (rows: horizontal on walls), height along v (up the
// panel); aspect = width / height. Two openings must always be separate regions of the open
// mask (at least one element apart, so that the mask and the rectangles describe the same
// openings), and at least `min_gap` apart.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "scene/facades.h"
#include "scene/mesh.h"
#include "scene/opening_domain.h"
#include "scene/window_catalogue.h"

namespace fenestra {

// Lengths in meters, areas in m^2. The defaults constrain nothing.
struct OpeningConstraints {
  static constexpr double kUnlimited = std::numeric_limits<double>::infinity();
  double min_area = 0.0, max_area = kUnlimited;
  double min_aspect = 0.0, max_aspect = kUnlimited;
  double min_width = 0.0, max_width = kUnlimited;
  double min_height = 0.0, max_height = kUnlimited;
  int max_openings = 0;  // over the whole domain; 0: unlimited
  double min_gap = 0.0;  // clear distance between the edges of two openings of one panel
  double margin = 0.0;   // clear distance from the panel's edges and holes, in whole elements of its grid
  // Openings' edges off the element grid land on multiples of this from the panel's grid corner
  // (meters); 0: anywhere (found to 1 cm). Not a limit: openings on the grid always qualify.
  double module = 0.0;
  // On walls only (normal within 30 degrees of horizontal), above the panel's base height.
  double sill_min = 0.0, sill_max = kUnlimited;
  double head_min = 0.0, head_max = kUnlimited;
  double head_clearance = 0.0;  // on walls: between the head and the panel's top
  // Openings per panel: at most max_openings_per_panel (0: unlimited), and at most one per
  // panel_width_per_opening meters of the panel's width (0: unlimited; panel_opening_limit()).
  int max_openings_per_panel = 0;
  double panel_width_per_opening = 0.0;
  // Facade composition (solve/composition.h), on flat walls; a facade is the coplanar wall panels,
  // and takes the rules of its first panel.
  bool align_sills = false, align_heads = false;  // one sill (head) height per facade
  // align_sills and align_heads set by "automatic" (neither given): kept only where they cost the
  // answer at most kAutomaticAlignmentCost of relative RMS error, else left out (and said so).
  bool automatic_alignment = false;
  bool equal_widths = false;                      // one width per facade
  bool same_type_in_row = false;                  // openings with one sill on a facade: one size
  bool symmetric = false;                         // each panel's openings mirror about its vertical axis
  bool equal_spacing = false;                     // equal piers between a facade's openings in a row
  std::vector<double> sill_heights;               // allowed sills, meters above the wall's base (empty: any)
  bool composes() const {
    return align_sills || align_heads || equal_widths || same_type_in_row || symmetric || equal_spacing ||
           !sill_heights.empty();
  }
  // The rules the user set (not the automatic alignment).
  bool composes_by_choice() const {
    return ((align_sills || align_heads) && !automatic_alignment) || equal_widths || same_type_in_row || symmetric ||
           equal_spacing || !sill_heights.empty();
  }
  // Empty: any size within the limits above. Otherwise every opening's size is one of the
  // catalogue's (on the kind of panel it lists sizes for); openings on the element grid are
  // snapped to it after the grid search (solve/catalogue_snap.h).
  WindowCatalogue catalogue;
  // World Z of each panel's lowest and highest points, which sills and heads are measured from
  // (panel_base_heights(), panel_top_heights()). Empty: the bottom and top of each panel's element
  // grid, which the grid's centring may move inside the panel's edges by up to half an element.
  std::vector<double> panel_base_z, panel_top_z;
  // The keys that took their automatic value (automatic_constraints()), for the result to say so.
  std::vector<std::string> automatic_keys;
  // Empty, or one set per panel that replaces these limits on that panel (max_openings stays
  // the global one).
  std::vector<OpeningConstraints> per_panel;

  const OpeningConstraints& for_panel(int panel) const {
    return per_panel.empty() ? *this : per_panel[static_cast<size_t>(panel)];
  }
  bool any() const;  // whether anything is constrained beyond plain rectangles
  std::string to_string() const;
};

// Automatic alignment of sills and heads is kept when it raises the relative RMS error by at most
// this: one point, one per cent of the goals' light.
inline constexpr double kAutomaticAlignmentCost = 0.01;

// What an opening is when the user says nothing: the value each key takes when it is not given
// and "automatic" is on. With full_height (doors and floor-to-ceiling glazing allowed), walls keep
// no automatic sill, head or margin limits.
struct AutomaticConstraint {
  const char* key;
  double value;
  const char* why;  // one line for the docs and the add-on's panel
};
// With climate goals (`climate`), openings also keep kClimateMinArea: a year's sDA and ASE are met
// by rooms' windows, not by holes of a quarter of a square meter in a corner.
std::vector<AutomaticConstraint> automatic_constraints(bool full_height, bool climate = false);
inline constexpr double kClimateMinArea = 1.0;  // m^2
// Sets `key` (one of automatic_constraints()' keys) to `value`.
void set_constraint(OpeningConstraints* c, const std::string& key, double value);

// Elements [row0, row1] x [col0, col1] (inclusive) of one panel.
struct GridRectangle {
  int panel = 0;
  int row0 = 0, row1 = 0, col0 = 0, col1 = 0;

  int rows() const { return row1 - row0 + 1; }
  int cols() const { return col1 - col0 + 1; }
  int element_count() const { return rows() * cols(); }
  bool operator==(const GridRectangle& o) const {
    return panel == o.panel && row0 == o.row0 && row1 == o.row1 && col0 == o.col0 && col1 == o.col1;
  }
  bool operator!=(const GridRectangle& o) const { return !(*this == o); }
  bool operator<(const GridRectangle& o) const;  // panel, then bottom-left corner, then size
  std::string to_string() const;
  // Rows and columns in order and not below 0 (a move may leave a rectangle otherwise).
  bool well_formed() const { return row0 <= row1 && col0 <= col1 && row0 >= 0 && col0 >= 0; }
  // Moved by whole elements along the rows and the columns.
  GridRectangle moved(int rows, int cols) const { return {panel, row0 + rows, row1 + rows, col0 + cols, col1 + cols}; }
  // Side 0..3 (left, right, bottom, top) moved out (step > 0) or in (step < 0) by `step` elements.
  GridRectangle side_moved(int side, int step) const {
    GridRectangle r = *this;
    switch (side) {
      case 0: r.col0 -= step; break;
      case 1: r.col1 += step; break;
      case 2: r.row0 -= step; break;
      default: r.row1 += step; break;
    }
    return r;
  }
};

// Throws std::invalid_argument naming the values when no grid-aligned opening (sides multiples
// of `element_size`) can meet the constraints, or a value is negative or not a number.
void check_feasible(const OpeningConstraints& constraints, double element_size);

// The constraints counted in whole elements (sizes are multiples of the element size).
struct GridLimits {
  int min_rows = 1, max_rows = 0, min_cols = 1, max_cols = 0;
  int64_t min_elements = 1, max_elements = 0;
  double min_aspect = 0.0, max_aspect = 0.0;
  int margin_elements = 0;  // whole elements kept clear around an opening (margin rounded up)
  int gap_elements = 1;     // whole elements between two openings side by side (min_gap, at least one)

  // Size, area and aspect ratio of a rows x cols opening.
  bool fits(int rows, int cols) const;
};
GridLimits grid_limits(const OpeningConstraints& constraints, double element_size);

// World heights (m) of a panel's base and top: from panel_base_z / panel_top_z where the
// constraints carry them (the faces' lowest and highest vertex), else its element grid's.
struct PanelHeights {
  double base = 0.0, top = 0.0;
};
PanelHeights wall_heights(const Panel& panel, int panel_index, const OpeningConstraints& constraints,
                          double element_size);
// Sill and head (m above the panel's base) of rows [row0, row1] of a panel's element grid.
struct RowHeights {
  double sill = 0.0, head = 0.0;
};
RowHeights row_heights(const Panel& panel, int row0, int row1, const PanelHeights& wall, double element_size);
// Sill and head limits of an opening spanning rows [row0, row1] of panel `panel_index`
// (true on roofs). Rows are horizontal on walls, so columns do not matter.
bool heights_ok(const Panel& panel, int panel_index, int row0, int row1, const OpeningConstraints& constraints,
                double element_size, std::string* why = nullptr);
// Per element of the domain, 1 where no admissible opening of whole elements can cover it: within
// the margin of its panel's edge (or of a square the panel lacks), or on a wall, a row below
// sill_min or above head_max or the head clearance. The solver's search leaves them closed.
std::vector<uint8_t> elements_out_of_bounds(const OpeningDomain& domain, const OpeningConstraints& constraints);

// World Z of the lowest and the highest vertex of each panel's faces.
std::vector<double> panel_base_heights(const OpeningDomain& domain, const Mesh& mesh);
std::vector<double> panel_top_heights(const OpeningDomain& domain, const Mesh& mesh);
// The most openings panel `panel_index` may hold under its constraints (0: unlimited):
// max_openings_per_panel, and one per panel_width_per_opening of the panel's width (on roofs,
// of each side: ceil(width / w) x ceil(height / w)), at least one.
int panel_opening_limit(const Panel& panel, int panel_index, const OpeningConstraints& constraints,
                        double element_size);

// One opening: inside its panel's grid on existing elements, `margin` clear of the panel's
// edges, and within the size, aspect, sill and head limits. `why` (optional) says what fails.
bool satisfies(const GridRectangle& rect, const Panel& panel, const OpeningConstraints& constraints,
               double element_size, std::string* why = nullptr);
// Clear distance between the edges of two openings of one panel (0 when they touch or
// overlap; infinity on different panels).
double clear_distance(const GridRectangle& a, const GridRectangle& b, double element_size);
// Whether two openings are separate regions and at least min_gap apart.
bool apart(const GridRectangle& a, const GridRectangle& b, const OpeningConstraints& constraints,
           double element_size);
// Every opening satisfies(), every pair is apart(), and there are at most max_openings (and at
// most panel_opening_limit() on each panel).
bool satisfies_all(const OpeningDomain& domain, const std::vector<GridRectangle>& rects,
                   const OpeningConstraints& constraints, std::string* why = nullptr);

// The open mask (one value per element of the domain) of a set of openings.
std::vector<uint8_t> rectangles_mask(const OpeningDomain& domain, const std::vector<GridRectangle>& rects);

// Empty when some catalogue size fits within a panel that has a catalogue (its extent less the
// margins, and on walls less the sill and head clearances), or no panel has one; otherwise why not,
// naming the largest room and the smallest size.
std::string catalogue_fit_problem(const OpeningDomain& domain, const OpeningConstraints& constraints);
// Empty, or why the composition rules cannot apply: a rule set where the domain has no flat wall.
std::string composition_problem(const OpeningDomain& domain, const OpeningConstraints& constraints);

}  // namespace fenestra
