#include "solve/edge_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <set>
#include <tuple>
#include <sstream>

#include "solve/region_search.h"
#include "util/progress.h"

namespace fenestra {
namespace {

constexpr double kTolerance = 1e-6;  // meters (and relative, for ratios): limits met within rounding
constexpr double kMinClearance = 0.01;  // meters between two openings of a panel, whatever min_gap says
constexpr int kMaxSweeps = 16;          // tries per step size, in cycles of all openings' moves
constexpr int kMaxScanPasses = 3;       // of EdgeSearchScope::scan_span over both axes
constexpr long kScanStride = 2;         // finest steps between the pairs a first pass tries every one of
constexpr size_t kRoughlyRankedPairs = 4;  // of those, evaluated in full after a rough ranking
constexpr size_t kScreenedFailures = 4;  // exact tries of a screened step's best-ranked moves before it ends

bool covers_elements(const OpeningDomain& domain, int panel, double u0, double u1, double v0, double v1) {
  const auto [c0, c1] = domain.columns_overlapping(panel, u0, u1);
  const auto [r0, r1] = domain.rows_overlapping(panel, v0, v1);
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c)
      if (domain.cell(panel, r, c) < 0) return false;
  return true;
}

std::string meters(double x) {
  std::ostringstream s;
  s << x << " m";
  return s.str();
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

// One edge (u0, u1, v0, v1: 0-3; the other -1), or two moved together, each by its sign times the
// step (times +-1).
struct EdgeMove {
  std::array<int, 2> edges;
  std::array<int, 2> signs;
};

// One edge at a time, or two opposite edges together (the opening slides along u or v).
const std::vector<EdgeMove>& straight_moves() {
  static const std::vector<EdgeMove> moves = {{{0, -1}, {1, 1}}, {{1, -1}, {1, 1}}, {{2, -1}, {1, 1}},
                                              {{3, -1}, {1, 1}}, {{0, 1}, {1, 1}},  {{2, 3}, {1, 1}}};
  return moves;
}

// An edge of each axis, either way each: width traded for height, along the valley of nearly equal
// light that coordinate moves cannot follow.
const std::vector<EdgeMove>& trading_moves() {
  static const std::vector<EdgeMove> moves = [] {
    std::vector<EdgeMove> m;
    for (int eu : {0, 1})
      for (int ev : {2, 3})
        for (int sign : {1, -1}) m.push_back({{eu, ev}, {1, sign}});
    return m;
  }();
  return moves;
}

const std::vector<EdgeMove>& straight_and_trading_moves() {
  static const std::vector<EdgeMove> moves = [] {
    std::vector<EdgeMove> m = straight_moves();
    m.insert(m.end(), trading_moves().begin(), trading_moves().end());
    return m;
  }();
  return moves;
}

// Whether opening i of `candidate` may be evaluated and kept: in a thick wall on the lines of the
// grid the records were traced on, on the records' elements, admissible, apart from the others.
bool fits(const OpeningDomain& domain, const OpeningConstraints& constraints,
          const std::vector<PanelRectangle>& candidate, size_t i, bool real_cuts) {
  const PanelRectangle& r = candidate[i];
  if (!real_cuts && domain.panels()[r.panel].thickness > 0.0f && !edges_on_grid_lines(domain, r)) return false;
  if (!covers_elements(domain, r.panel, r.u0, r.u1, r.v0, r.v1) || !admissible(r, domain, constraints))
    return false;
  for (size_t j = 0; j < candidate.size(); ++j)
    if (j != i && !apart(r, candidate[j], constraints)) return false;
  return true;
}

// EdgeSearchScope::scan_span: pairs of positions of an opening's two edges along one axis (real
// cuts: any position), within `span` of where they start, `step` apart. Every pair `stride` steps
// apart first (a valley between coarser pairs is easily missed), ranked by rough values and the
// best few evaluated; then the 3 x 3 pairs about the best at halving strides down to one step,
// moving with the best until it stays. Returns whether a pair was kept.
bool scan_edge_pairs(const OpeningDomain& domain, const OpeningConstraints& constraints, const LinearObjective& objective,
                     const Eigen::VectorXd& closed, double span, double step, long stride, int only_opening,
                     RegionQueries* search, double* error, EdgeRefinement* out, Progress* progress) {
  bool kept = false;
  const long k = static_cast<long>(std::floor(span / step + 1e-9));
  if (k < 1) return false;
  for (size_t i = 0; i < search->rectangles().size(); ++i) {
    const Panel& panel = domain.panels()[search->rectangles()[i].panel];
    if (!(panel.thickness > 0.0f) || (only_opening >= 0 && i != static_cast<size_t>(only_opening))) continue;
    for (int axis = 0; axis < 2; ++axis) {
      const PanelRectangle start = search->rectangles()[i];
      const double lo = axis == 0 ? start.u0 : start.v0, hi = axis == 0 ? start.u1 : start.v1;
      std::set<std::pair<long, long>> tried = {{0, 0}};
      std::vector<PanelRectangle> best;
      long best_a = 0, best_b = 0;  // offsets of the low and high edges, in steps
      // The openings with the pair (a, b), if it lies within the span and fits.
      auto pair_fits = [&](long a, long b, std::vector<PanelRectangle>* candidate) {
        if (std::abs(a) > k || std::abs(b) > k) return false;
        const double low = lo + static_cast<double>(a) * step, high = hi + static_cast<double>(b) * step;
        if (!(static_cast<float>(high) > static_cast<float>(low))) return false;
        if (progress) progress->throw_if_cancelled();
        *candidate = search->rectangles();
        PanelRectangle& r = (*candidate)[i];
        (axis == 0 ? r.u0 : r.v0) = static_cast<float>(low);
        (axis == 0 ? r.u1 : r.v1) = static_cast<float>(high);
        return fits(domain, constraints, *candidate, i, true);
      };
      auto try_pair = [&](long a, long b) {
        std::vector<PanelRectangle> candidate;
        if (!tried.insert({a, b}).second || !pair_fits(a, b, &candidate)) return;
        const double e = prediction_error(objective, search->try_region(candidate) - closed);
        ++out->evaluations;
        if (e < *error * (1.0 - 1e-9)) *error = e, best = candidate, best_a = a, best_b = b;
      };
      if (stride > 1) {
        // Ranked by rough values, the best few evaluated.
        std::vector<std::tuple<double, long, long>> ranked;
        for (long a = -(k / stride) * stride; a <= k; a += stride)
          for (long b = -(k / stride) * stride; b <= k; b += stride) {
            std::vector<PanelRectangle> candidate;
            if (!(a == 0 && b == 0) && pair_fits(a, b, &candidate))
              ranked.emplace_back(prediction_error(objective, search->rough_values(candidate) - closed), a, b);
          }
        std::sort(ranked.begin(), ranked.end());
        for (size_t n = 0; n < ranked.size() && n < kRoughlyRankedPairs; ++n)
          try_pair(std::get<1>(ranked[n]), std::get<2>(ranked[n]));
      }
      for (long about = stride > 1 ? stride / 2 : 1; about >= 1; about /= 2) {
        long ca = 0, cb = 0;
        do {
          ca = best_a, cb = best_b;
          for (long da = -1; da <= 1; ++da)
            for (long db = -1; db <= 1; ++db) try_pair(ca + da * about, cb + db * about);
        } while (best_a != ca || best_b != cb);
      }
      if (best.empty()) continue;
      // Evaluated again (the search remembers its last try only), and kept.
      search->try_region(best);
      search->accept();
      ++out->moves;
      kept = true;
    }
  }
  return kept;
}

// Area of an element's cell inside r, m^2.
double area_within(const Element& e, const PanelRectangle& r) {
  const double du = std::min<double>(e.u1, r.u1) - std::max<double>(e.u0, r.u0);
  const double dv = std::min<double>(e.v1, r.v1) - std::max<double>(e.v0, r.v0);
  return du > 0.0 && dv > 0.0 ? du * dv : 0.0;
}

}  // namespace

Eigen::VectorXd screened_values(const OpeningDomain& domain, const Eigen::MatrixXd& opening_light,
                                const Eigen::VectorXd& values, const PanelRectangle& from, const PanelRectangle& to) {
  Eigen::VectorXd out = values;
  const auto [c0, c1] = domain.columns_overlapping(from.panel, std::min(from.u0, to.u0), std::max(from.u1, to.u1));
  const auto [r0, r1] = domain.rows_overlapping(from.panel, std::min(from.v0, to.v0), std::max(from.v1, to.v1));
  for (int row = std::max(r0, 0); row <= r1; ++row)
    for (int col = std::max(c0, 0); col <= c1; ++col) {
      const int k = domain.cell(from.panel, row, col);
      if (k < 0) continue;
      const Element& e = domain.elements()[static_cast<size_t>(k)];
      const double share = (area_within(e, to) - area_within(e, from)) / (e.width() * e.height());
      if (share != 0.0) out += share * opening_light.col(k);
    }
  return out;
}

std::vector<double> edge_steps(double s, double module, bool thick) {
  const double smallest = std::max(module > 0.0 ? module : kContinuousEdgeStep, thick ? kThickWallEdgeStep : 0.0);
  std::vector<double> steps = {s};
  for (double step = 0.5 * s; step >= smallest * (1.0 - 1e-9);) {
    const double snapped = module > 0.0 ? std::max(module, snap(step, module)) : step;
    if (thick && snapped < kThickWallEdgeStep * (1.0 - 1e-9)) break;
    if (snapped < steps.back() * (1.0 - 1e-9)) steps.push_back(snapped);
    if (module > 0.0 && snapped <= module * (1.0 + 1e-9)) break;
    step = 0.5 * snapped;
  }
  return steps;
}

double thick_wall_edge_span(double s, double module) {
  const std::vector<double> steps = edge_steps(s, module, true);
  if (steps.size() < 2) return 0.0;
  double reach = 0.0;
  for (size_t i = 1; i < steps.size(); ++i) reach += steps[i];
  return s + reach;
}

std::vector<float> edge_positions(double edge, double s, double module, bool thick) {
  const std::vector<double> steps = edge_steps(s, module, thick);
  std::vector<float> out;
  if (steps.size() < 2) return out;
  const double span = thick ? thick_wall_edge_span(s, module) : s;
  // Module multiples, or the edge plus multiples of the finest step (halving steps add up to them).
  const double unit = module > 0.0 ? module : steps.back();
  const double base = module > 0.0 ? 0.0 : edge;
  const long first = static_cast<long>(std::ceil((edge - span - base) / unit - 1e-9));
  const long last = static_cast<long>(std::floor((edge + span - base) / unit + 1e-9));
  for (long k = first; k <= last; ++k) out.push_back(static_cast<float>(base + k * unit));
  return out;
}

PanelRectangle panel_rectangle(const GridRectangle& r, double s) {
  return {r.panel, r.col0 * s, (r.col1 + 1) * s, r.row0 * s, (r.row1 + 1) * s};
}

bool admissible(const PanelRectangle& r, const OpeningDomain& domain, const OpeningConstraints& all, std::string* why) {
  const OpeningConstraints& c = all.for_panel(r.panel);
  const Panel& panel = domain.panels()[r.panel];
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  const double w = r.width(), h = r.height();
  if (!(w > kContinuousEdgeStep - kTolerance && h > kContinuousEdgeStep - kTolerance))
    return fail("is narrower than " + meters(kContinuousEdgeStep));
  if (!covers_elements(domain, r.panel, r.u0, r.u1, r.v0, r.v1)) return fail("leaves the panel's elements");
  const double m = c.margin;
  if (m > 0.0 && !covers_elements(domain, r.panel, r.u0 - m, r.u1 + m, r.v0 - m, r.v1 + m))
    return fail("lies closer than margin " + meters(m) + " to the panel's edge");
  if (w < c.min_width - kTolerance || w > c.max_width + kTolerance) return fail("has width " + meters(w) + " out of its limits");
  if (h < c.min_height - kTolerance || h > c.max_height + kTolerance)
    return fail("has height " + meters(h) + " out of its limits");
  if (w * h < c.min_area * (1 - kTolerance) || w * h > c.max_area * (1 + kTolerance)) return fail("has an area out of its limits");
  if (w / h < c.min_aspect * (1 - kTolerance) || w / h > c.max_aspect * (1 + kTolerance))
    return fail("has an aspect ratio out of its limits");
  if (!c.catalogue.allows(panel, w, h)) return fail("is " + meters(w) + " x " + meters(h) + ", not a size of the catalogue");
  if (is_wall(panel)) {
    const PanelHeights wall = wall_heights(panel, r.panel, all, domain.element_size());
    const double z0 = panel.origin.z() + r.v0 * panel.v_axis.z(), z1 = panel.origin.z() + r.v1 * panel.v_axis.z();
    const double sill = std::min(z0, z1) - wall.base, head = std::max(z0, z1) - wall.base;
    if (sill < c.sill_min - kTolerance || sill > c.sill_max + kTolerance) return fail("has its sill out of its limits");
    if (head < c.head_min - kTolerance || head > c.head_max + kTolerance) return fail("has its head out of its limits");
    if (c.head_clearance > 0.0) {
      if (std::max(z0, z1) > wall.top - c.head_clearance + kTolerance)
        return fail("has its head less than head_clearance " + meters(c.head_clearance) + " below the wall's top");
    }
  }
  return true;
}

bool apart(const PanelRectangle& a, const PanelRectangle& b, const OpeningConstraints& c) {
  if (a.panel != b.panel) return true;
  const double gap_u = std::max({0.0, b.u0 - a.u1, a.u0 - b.u1}), gap_v = std::max({0.0, b.v0 - a.v1, a.v0 - b.v1});
  const double d = std::hypot(gap_u, gap_v);
  return d >= std::max(kMinClearance, c.for_panel(a.panel).min_gap) - kTolerance;
}

std::vector<std::string> constraint_violations(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings,
                                               const OpeningConstraints& constraints) {
  std::vector<std::string> out;
  const int panels = static_cast<int>(domain.panels().size());
  auto name = [](size_t i) { return "opening " + std::to_string(i); };
  std::vector<int> count(static_cast<size_t>(panels), 0);
  for (size_t i = 0; i < openings.size(); ++i) {
    const PanelRectangle& r = openings[i];
    if (r.panel < 0 || r.panel >= panels) {
      out.push_back(name(i) + " names no panel of the domain");
      continue;
    }
    ++count[static_cast<size_t>(r.panel)];
    std::string why;
    if (!admissible(r, domain, constraints, &why)) out.push_back(name(i) + " " + why);
    for (size_t j = i + 1; j < openings.size(); ++j)
      if (!apart(r, openings[j], constraints))
        out.push_back(name(i) + " and " + name(j) + " are closer than min_gap " +
                      meters(std::max(kMinClearance, constraints.for_panel(r.panel).min_gap)));
  }
  if (constraints.max_openings > 0 && static_cast<int>(openings.size()) > constraints.max_openings)
    out.push_back(std::to_string(openings.size()) + " openings, more than max_openings " +
                  std::to_string(constraints.max_openings));
  for (int p = 0; p < panels; ++p) {
    const int limit = panel_opening_limit(domain.panels()[p], p, constraints, domain.element_size());
    if (limit > 0 && count[static_cast<size_t>(p)] > limit)
      out.push_back("panel " + std::to_string(p) + " has " + std::to_string(count[static_cast<size_t>(p)]) +
                    " openings, more than its limit " + std::to_string(limit));
  }
  return out;
}

EdgeRefinement refine_edges(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                            const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                            Progress* progress, const EdgeSearchScope& scope) {
  const std::unique_ptr<RegionQueries> search = records.region_search(start);
  return refine_edges(domain, records.contributions().closed.value, objective, constraints, search.get(), progress,
                      scope);
}

EdgeRefinement refine_edges(const OpeningDomain& domain, const Eigen::VectorXd& closed,
                            const LinearObjective& objective, const OpeningConstraints& constraints,
                            RegionQueries* searched_region, Progress* progress, const EdgeSearchScope& scope) {
  const double s = domain.element_size();
  EdgeRefinement out;
  RegionQueries& search = *searched_region;
  double error = prediction_error(objective, search.values() - closed);
  const double module = constraints.module;
  // Width and height trade against each other (a valley of nearly equal light): the axes are
  // scanned in turn while either improves, over the whole span first, then within two steps,
  // following the best from one step about it.
  const double finest = edge_steps(s, constraints.module, true).back();
  bool scans_settled = false;  // a whole pass kept nothing
  for (int pass = 0; scope.scan_span > 0.0 && scope.real_cuts && pass < kMaxScanPasses && !scans_settled; ++pass) {
    const double span = pass == 0 ? scope.scan_span : std::min(scope.scan_span, 2.0 * finest);
    const long stride = pass == 0 ? kScanStride : 1;
    scans_settled = !scan_edge_pairs(domain, constraints, objective, closed, span, finest, stride, scope.only_opening,
                                     &search, &error, &out, progress);
  }
  const std::vector<EdgeMove>& moves = scope.scan_span > 0.0 ? straight_and_trading_moves() : straight_moves();
  // The openings with opening i's edges moved by `step` (move, direction), if that changes and fits.
  auto moved = [&](size_t i, const EdgeMove& move, double direction, double step, bool whole_elements,
                   std::vector<PanelRectangle>* candidate) {
    *candidate = search.rectangles();
    PanelRectangle& r = (*candidate)[i];
    bool changed = true;
    for (int k = 0; k < 2; ++k) {
      const int edge = move.edges[k];
      if (edge < 0) continue;
      const double from = edge_of(r, edge);
      const double by = direction * move.signs[k] * step;
      edge_of(r, edge) = whole_elements ? from + by : snap(from + by, module);
      changed = changed && edge_of(r, edge) != from;
    }
    return changed && fits(domain, constraints, *candidate, i, scope.real_cuts);
  };
  // Kept when the exact error falls.
  auto try_move = [&](size_t i, const EdgeMove& move, double direction, double step, bool whole_elements) {
    std::vector<PanelRectangle> candidate;
    if (!moved(i, move, direction, step, whole_elements, &candidate)) return false;
    const Eigen::VectorXd& values = search.try_region(candidate);
    ++out.evaluations;
    const double e = prediction_error(objective, values - closed);
    if (!(e < error * (1.0 - 1e-9))) return false;
    search.accept();
    error = e;
    ++out.moves;
    return true;
  };
  const size_t cycle = search.rectangles().size() * moves.size() * 2;
  // Try t of a cycle: opening t / (2 moves), move t / 2, direction by t's parity.
  auto opening_of = [&](size_t t) { return t / (moves.size() * 2) % search.rectangles().size(); };
  auto move_of = [&](size_t t) -> const EdgeMove& { return moves[t / 2 % moves.size()]; };
  auto direction_of = [](size_t t) { return t % 2 ? 1.0 : -1.0; };
  auto try_nth = [&](size_t t, double step, bool whole_elements) {
    return try_move(opening_of(t), move_of(t), direction_of(t), step, whole_elements);
  };
  auto thick = [&](size_t i) { return domain.panels()[search.rectangles()[i].panel].thickness > 0.0f; };
  auto searched = [&](size_t i) {
    if (scope.only_opening >= 0 && i != static_cast<size_t>(scope.only_opening)) return false;
    return thick(i) ? scope.thick_panels : scope.zero_thickness_panels;
  };
  // The screen is linear: in thick walls, where elements open together pass much more light than
  // apart (reveals, oblique paths), it misranks moves, so those openings are not screened.
  auto screened = [&](size_t i) { return scope.opening_light && !thick(i) && searched(i); };
  // The screened openings' moves in the order of the error the screen predicts, evaluated exactly
  // until kScreenedFailures in a row fail.
  auto screened_step = [&](double step, bool whole_elements) {
    for (size_t round = 0; round < kMaxSweeps * cycle; ++round) {  // a move kept per round
      std::vector<std::pair<double, size_t>> ranked;
      for (size_t t = 0; t < cycle; ++t) {
        const size_t i = opening_of(t);
        if (!screened(i)) continue;
        std::vector<PanelRectangle> candidate;
        if (!moved(i, move_of(t), direction_of(t), step, whole_elements, &candidate)) continue;
        const Eigen::VectorXd predicted =
            screened_values(domain, *scope.opening_light, search.values(), search.rectangles()[i], candidate[i]);
        ranked.push_back({prediction_error(objective, predicted - closed), t});
      }
      std::sort(ranked.begin(), ranked.end());
      bool improved = false;
      for (size_t n = 0; n < ranked.size() && n < kScreenedFailures && !improved; ++n) {
        if (progress) progress->throw_if_cancelled();
        improved = try_nth(ranked[n].second, step, whole_elements);
      }
      if (!improved) return;
    }
  };
  std::vector<double> steps = edge_steps(s, module, !scope.zero_thickness_panels);
  while (scope.coarsest_finest_step > 0.0 && steps.size() > 1 &&
         steps[steps.size() - 2] >= scope.coarsest_finest_step * (1.0 - 1e-9))
    steps.pop_back();
  // The pair scans tried every move of an edge, and every slide, by one of the finest steps about
  // where each pass ended: only the finest step's moves follow (those that trade width for height
  // are new).
  if (scope.scan_span > 0.0 && scope.real_cuts) steps.erase(steps.begin(), steps.end() - 1);
  // A settled scan tried every straight move of one step about where each opening ended: unless a
  // move that trades width for height gains there, the search has ended.
  auto a_trade_gains = [&] {
    for (size_t i = 0; i < search.rectangles().size(); ++i)
      for (const EdgeMove& move : trading_moves())
        for (const double direction : {-1.0, 1.0}) {
          if (progress) progress->throw_if_cancelled();
          if (searched(i) && try_move(i, move, direction, finest, false)) return true;
        }
    return false;
  };
  if (scans_settled && !a_trade_gains()) steps.clear();
  for (const double step : steps) {
    const bool whole_elements = step >= s * (1.0 - 1e-9);
    if (whole_elements && !scope.whole_elements) continue;
    const bool finest = step == steps.back();
    if (scope.opening_light && !finest) screened_step(step, whole_elements);
    // Every opening's moves in turn (at the coarser steps, those the screen left), until a whole
    // cycle of them since the last one kept has failed: each was then tried against the openings
    // as they ended. The finest step tries every move of every opening.
    for (size_t t = 0, failed = 0, tries = 0; failed < cycle && tries < kMaxSweeps * cycle; ++tries) {
      const size_t i = opening_of(t);
      if (progress) progress->throw_if_cancelled();
      const bool kept = searched(i) && (finest || !screened(i)) && try_nth(t, step, whole_elements);
      failed = kept ? 0 : failed + 1;
      if (!kept) ++t;  // a kept move is tried again at once: an edge often travels several steps
    }
  }
  out.openings = search.rectangles();
  return out;
}

}  // namespace fenestra
