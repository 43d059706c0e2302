#pragma once
// Facade composition: the openings of each facade (its coplanar flat wall panels) made to share a
// sill height (align_sills, or one of sill_heights), a head height (align_heads), a width
// (equal_widths; same_type_in_row: one size per row of equal sills), to mirror about each panel's
// vertical axis (symmetric), and to leave equal piers between them (equal_spacing).
//
// Each rule, in that order, turns the openings into a few candidate sets that keep it and the
// rules before it (every distinct sill, head or width of the facade's openings as the common one;
// the left or the right half mirrored; the row's piers evened out between its outer edges), and
// the candidate the error function scores best, among those whose openings stay admissible and
// apart, is kept. Then a local search over moves that keep the rules so far (a facade's sills,
// heads or widths all together, an opening sliding along its wall) lets the openings recover what
// they can. What each rule costs is reported: the error before it and after its search. Sills and
// heads aligned automatically (automatic_alignment) are tried only on facades with two openings or
// more, and undone when they cost more than kAutomaticAlignmentCost.
#include <functional>
#include <string>
#include <vector>

#include "scene/facades.h"
#include "scene/opening_constraints.h"
#include "trace/open_region.h"

namespace fenestra {

class Progress;

struct CompositionStep {
  std::string rule;                // the constraint's key
  double error_before = 0.0, error_after = 0.0;  // of the error function (relative RMS)
  bool met = true;                 // false: no candidate kept the openings admissible
  // An automatic rule (automatic_alignment): kept only where it met and cost at most
  // kAutomaticAlignmentCost; else the openings are as before it (error_after: what it would cost).
  bool automatic = false, kept = true;
};

struct Composition {
  std::vector<PanelRectangle> openings;
  std::vector<CompositionStep> steps;  // the rules that apply, in order
};


// `error_of` scores a set of openings (lower is better).
Composition compose_facades(const OpeningDomain& domain, const OpeningConstraints& constraints,
                            const std::vector<PanelRectangle>& openings,
                            const std::function<double(const std::vector<PanelRectangle>&)>& error_of,
                            Progress* progress);


// What the openings break of the composition rules (one line each).
std::vector<std::string> composition_violations(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                                const std::vector<PanelRectangle>& openings);

}  // namespace fenestra
