#pragma once
// Openings found on the element grid, given the sizes of a window catalogue
// (solver.constraints.catalogue). For each opening in turn (two passes), every catalogue size of
// its panel, placed centred where the opening was, on its sill, or under its head (moved by the
// least that makes it admissible), and no opening at all, are ranked by the linear model about the
// grid's openings; the best few are evaluated exactly from the path records and the best kept. An
// opening whose size is not in the catalogue is always replaced; one with no admissible size is
// dropped, and a note says why.
//
// In thick walls the records are exact only on the element grid's lines, and the linear model
// misjudges whole openings there (elements open together pass much more light than apart): with
// `cut_paths` > 0, every candidate is scored by a real cut (RecordQueries::cut, that many paths
// per sensor, on the thick-wall edge search's stream). Without, resized openings in thick walls are
// scored by the linear model alone, and the solver cuts them for the prediction.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/opening_constraints.h"
#include "solve/genetic.h"
#include "solve/record_queries.h"
#include "trace/contributions.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

struct CatalogueSnap {
  std::vector<PanelRectangle> openings;
  Eigen::VectorXd values;          // per sensor: exact, but linear for resized openings in thick walls
  bool exact = true;               // false when an opening in a thick wall was resized without cuts
  Eigen::VectorXd standard_error;  // with cuts: per sensor, the values' (else empty)
  std::vector<std::string> notes;  // openings dropped for want of an admissible size
};


// The constraints the element-grid search works with: on panels with a catalogue, sizes within
// an element of the catalogue's range (so that the grid's openings are near a catalogue size),
// where that is feasible.
OpeningConstraints grid_search_constraints(const OpeningDomain& domain, const OpeningConstraints& constraints);

// Whether some panel's catalogue applies (snap_to_catalogue has work to do).
bool uses_catalogue(const OpeningDomain& domain, const OpeningConstraints& constraints);

// `start`: the grid's openings (satisfies_all). `opening_light`: sensors x elements, the light each
// element adds when opened about `start` (the solver's linearisation).
CatalogueSnap snap_to_catalogue(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                                const OpeningConstraints& constraints, const Eigen::MatrixXd& opening_light,
                                const std::vector<PanelRectangle>& start, Progress* progress, int cut_paths = 0);

}  // namespace fenestra
