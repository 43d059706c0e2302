#include "solve/refinable_openings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "solve/edge_refinement.h"
#include "util/progress.h"

namespace fenestra {
namespace {

using Openings = std::vector<GridRectangle>;

// Coordinate sweeps of the interpolation's least squares, and the step (elements) that ends them.
constexpr int kMaxSweeps = 100;
constexpr double kConverged = 1e-5;
// A move smaller than this share of the error is no gain (rounding, not light).
constexpr double kRelativeGain = 1e-9;

// Within its panel's grid (the records evaluate no other).
bool on_its_panel(const OpeningDomain& domain, const GridRectangle& r) {
  if (!r.well_formed() || r.panel < 0 || static_cast<size_t>(r.panel) >= domain.panels().size()) return false;
  const Panel& p = domain.panels()[static_cast<size_t>(r.panel)];
  return r.row1 < p.rows && r.col1 < p.cols;
}

bool all_on_their_panels(const OpeningDomain& domain, const Openings& set) {
  return std::all_of(set.begin(), set.end(), [&](const GridRectangle& r) { return on_its_panel(domain, r); });
}

Openings sorted(Openings set) {
  std::sort(set.begin(), set.end());
  return set;
}

// The neighbours of a set: each opening removed, or moved by an element along either axis, or one
// side out or in; with which opening changed (index into `set`) and whether it was removed.
struct Neighbour {
  Openings set;
  size_t opening;
  bool removed;
};

std::vector<Neighbour> neighbours(const Openings& set) {
  std::vector<Neighbour> out;
  // Removals first: an opening that a neighbour could replace once moved would otherwise move
  // toward its light and stay (a pair where the truth has one).
  for (size_t i = 0; i < set.size(); ++i) {
    Openings fewer = set;
    fewer.erase(fewer.begin() + static_cast<std::ptrdiff_t>(i));
    out.push_back({std::move(fewer), i, true});
  }
  for (size_t i = 0; i < set.size(); ++i) {
    auto with = [&](const GridRectangle& r) {
      Openings changed = set;
      changed[i] = r;
      out.push_back({std::move(changed), i, false});
    };
    for (int side = 0; side < 4; ++side)
      for (int step : {1, -1}) with(set[i].side_moved(side, step));
    for (auto [rows, cols] : {std::pair{0, -1}, {0, 1}, {-1, 0}, {1, 0}}) with(set[i].moved(rows, cols));
  }
  return out;
}

class Descent {
 public:
  Descent(const OpeningDomain& domain, const OpeningConstraints& constraints, const OpeningValues& values_of,
          const LinearObjective& objective, int max_evaluations, const Progress* progress)
      : domain_(domain), constraints_(constraints), values_of_(values_of), objective_(objective),
        max_evaluations_(max_evaluations), progress_(progress) {}

  // Exact values of a set, once per set; nullopt when the evaluations ran out.
  const Eigen::VectorXd* values(const Openings& set) {
    const Openings key = sorted(set);
    const auto known = known_.find(key);
    if (known != known_.end()) return &known->second;
    if (max_evaluations_ > 0 && evaluations_ >= max_evaluations_) {
      out_of_evaluations_ = true;
      return nullptr;
    }
    if (progress_) progress_->throw_if_cancelled();
    ++evaluations_;
    return &known_.emplace(key, values_of_(key)).first->second;
  }

  // The side light of `set` about `base` (its values); false when the evaluations ran out.
  bool side_light_of(const Openings& set, const Eigen::VectorXd& base, SideLight* sides) {
    std::vector<Eigen::VectorXd> out, in;
    std::vector<size_t> opening;
    for (size_t i = 0; i < set.size(); ++i)
      for (int side = 0; side < 4; ++side) {
        Eigen::VectorXd moved[2];
        for (int k = 0; k < 2; ++k) {
          Openings changed = set;
          changed[i] = set[i].side_moved(side, k == 0 ? 1 : -1);
          if (!on_its_panel(domain_, changed[i])) continue;
          const Eigen::VectorXd* v = values(changed);
          if (!v) return false;
          moved[k] = *v - base;
        }
        out.push_back(std::move(moved[0]));
        in.push_back(std::move(moved[1]));
        opening.push_back(i);
      }
    *sides = side_light(out, in, opening, base.size());
    // Only as far as the constraints let every side go at once (each opening's four in order).
    std::vector<PanelRectangle> placed;
    for (const GridRectangle& r : set) placed.push_back(panel_rectangle(r, domain_.element_size()));
    for (size_t j = 0; j < opening.size(); ++j) {
      const auto c = static_cast<Eigen::Index>(j);
      const int side = static_cast<int>(j % 4);
      sides->high[c] = std::min(sides->high[c], side_reach(domain_, constraints_, placed, opening[j], side, true));
      sides->low[c] = std::max(sides->low[c], -side_reach(domain_, constraints_, placed, opening[j], side, false));
    }
    return true;
  }

  // The interpolated error of `set`, from its own side light; nullopt when the evaluations ran out.
  std::optional<double> scored(const Openings& set, SideLight* sides) {
    const Eigen::VectorXd* base = values(set);
    if (!base) return std::nullopt;
    // The map's nodes stay where they are as side_light_of adds sets: *base stays valid.
    if (!side_light_of(set, *base, sides)) return std::nullopt;
    return interpolated_error(objective_, *base, *sides);
  }

  // Descents from the `descents` starts (within the constraints) whose interpolated errors are
  // lowest, the lowest first; the best answer.
  RefinableOpenings run(const std::vector<Openings>& starts, size_t descents) {
    std::vector<std::pair<double, Openings>> ranked;
    std::vector<double> start_errors(starts.size(), std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < starts.size(); ++i) {
      const Openings& start = starts[i];
      if (start.empty() || !all_on_their_panels(domain_, start) || !satisfies_all(domain_, start, constraints_))
        continue;
      SideLight sides;
      const std::optional<double> e = scored(start, &sides);
      if (!e) break;
      start_errors[i] = *e;
      ranked.push_back({*e, sorted(start)});
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    RefinableOpenings best;
    best.error = std::numeric_limits<double>::infinity();
    for (size_t d = 0; d < ranked.size() && d < descents && !out_of_evaluations_; ++d) {
      RefinableOpenings found = descend(ranked[d].second);
      if (found.error < best.error) best = std::move(found), best.start = static_cast<int>(d);
    }
    best.start_errors = std::move(start_errors);
    return finish(best);
  }

 private:
  RefinableOpenings descend(const Openings& start) {
    RefinableOpenings out;
    Openings current = sorted(start);
    SideLight sides;
    const std::optional<double> first = scored(current, &sides);
    out.rects = current;
    out.error = std::numeric_limits<double>::infinity();
    if (!first) return out;
    out.start_error = out.error = *first;
    for (bool improved = true; improved;) {
      improved = false;
      for (const Neighbour& n : neighbours(current)) {
        if (!all_on_their_panels(domain_, n.set) || !satisfies_all(domain_, n.set, constraints_)) continue;
        const Eigen::VectorXd* v = values(n.set);
        if (!v) return out;
        // The screen: the neighbour's values with the current set's side light (less the removed
        // opening's); only a neighbour it finds better is scored with its own.
        const double screen = interpolated_error(objective_, *v, n.removed ? sides.without(n.opening) : sides);
        if (!(screen < out.error * (1.0 - kRelativeGain))) continue;
        SideLight its_sides;
        const std::optional<double> e = scored(n.set, &its_sides);
        if (!e) return out;
        if (!(*e < out.error * (1.0 - kRelativeGain))) continue;
        current = n.set;
        sides = std::move(its_sides);
        out.rects = sorted(current);
        out.error = *e;
        ++out.moves;
        improved = true;
        break;
      }
    }
    return out;
  }

  RefinableOpenings finish(RefinableOpenings out) const {
    out.evaluations = evaluations_;
    out.out_of_evaluations = out_of_evaluations_;
    return out;
  }

  const OpeningDomain& domain_;
  const OpeningConstraints& constraints_;
  const OpeningValues& values_of_;
  const LinearObjective& objective_;
  const int max_evaluations_;
  const Progress* progress_;
  std::map<Openings, Eigen::VectorXd> known_;
  int evaluations_ = 0;
  bool out_of_evaluations_ = false;
};

}  // namespace

namespace {

// The size limits (width, height, area) of an opening grown (or shrunk) by `by` on every side.
bool within_size_limits(const PanelRectangle& r, double by, const OpeningConstraints& c) {
  const double w = r.width() + 2.0 * by, h = r.height() + 2.0 * by, tolerance = 1e-6;
  return w >= c.min_width - tolerance && w <= c.max_width + tolerance && h >= c.min_height - tolerance &&
         h <= c.max_height + tolerance && w * h >= c.min_area - tolerance && w * h <= c.max_area + tolerance;
}

}  // namespace

double side_reach(const OpeningDomain& domain, const OpeningConstraints& constraints,
                  const std::vector<PanelRectangle>& openings, size_t i, int side, bool out, double reach) {
  const double s = domain.element_size();
  const OpeningConstraints& c = constraints.for_panel(openings[i].panel);
  for (double share : {1.0, 0.75, 0.5, 0.25}) {
    const double by = share * reach * s * (out ? 1.0 : -1.0);  // outward, meters
    PanelRectangle r = openings[i];
    switch (side) {
      case 0: r.u0 -= by; break;
      case 1: r.u1 += by; break;
      case 2: r.v0 -= by; break;
      default: r.v1 += by; break;
    }
    if (!admissible(r, domain, constraints) || !within_size_limits(openings[i], by, c)) continue;
    bool apart_from_all = true;
    for (size_t j = 0; j < openings.size() && apart_from_all; ++j) {
      if (j == i) continue;
      PanelRectangle o = openings[j];
      const double grown = std::max(0.0, by);
      o.u0 -= grown, o.u1 += grown, o.v0 -= grown, o.v1 += grown;
      apart_from_all = apart(r, o, constraints);
    }
    if (apart_from_all) return share * reach;
  }
  return 0.0;
}

SideLight SideLight::without(size_t i) const {
  std::vector<Eigen::Index> kept;
  for (size_t j = 0; j < opening.size(); ++j)
    if (opening[j] != i) kept.push_back(static_cast<Eigen::Index>(j));
  SideLight out;
  out.slope.resize(slope.rows(), static_cast<Eigen::Index>(kept.size()));
  out.curve.resize(curve.rows(), static_cast<Eigen::Index>(kept.size()));
  out.low.resize(static_cast<Eigen::Index>(kept.size()));
  out.high.resize(static_cast<Eigen::Index>(kept.size()));
  for (size_t k = 0; k < kept.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    out.slope.col(c) = slope.col(kept[k]);
    out.curve.col(c) = curve.col(kept[k]);
    out.low[c] = low[kept[k]];
    out.high[c] = high[kept[k]];
    out.opening.push_back(opening[static_cast<size_t>(kept[k])]);
  }
  return out;
}

SideLight side_light(const std::vector<Eigen::VectorXd>& out, const std::vector<Eigen::VectorXd>& in,
                     const std::vector<size_t>& opening, Eigen::Index sensors, double reach) {
  const auto m = static_cast<Eigen::Index>(opening.size());
  SideLight s;
  s.slope.setZero(sensors, m);
  s.curve.setZero(sensors, m);
  s.low.setZero(m);
  s.high.setZero(m);
  s.opening = opening;
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXd& o = out[static_cast<size_t>(j)];
    const Eigen::VectorXd& i = in[static_cast<size_t>(j)];
    if (o.size() && i.size()) {
      s.slope.col(j) = 0.5 * (o - i);
      s.curve.col(j) = 0.5 * (o + i);
      s.low[j] = -reach, s.high[j] = reach;
    } else if (o.size()) {
      s.slope.col(j) = o, s.high[j] = reach;
    } else if (i.size()) {
      s.slope.col(j) = -i, s.low[j] = -reach;
    }
  }
  return s;
}

namespace {

// The objective's gradient and Gauss-Newton curvature along side j at p (values for s), and the
// curvature the parabolas add.
struct AlongSide {
  double gradient = 0.0, gauss_newton = 0.0, from_curve = 0.0;
};

AlongSide along_side(const LinearObjective& o, const Eigen::VectorXd& p, const SideLight& sides, Eigen::Index j,
                     double s) {
  AlongSide a;
  const bool lower = o.lower.size() > 0, upper = o.upper.size() > 0;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    const double w = o.weight[i];
    if (!(w > 0.0)) continue;
    const double g = sides.slope(i, j) + 2.0 * sides.curve(i, j) * s;  // dp_i / ds
    const double below = lower ? std::max(0.0, o.lower[i] - p[i]) : 0.0;
    const double above = upper ? std::max(0.0, p[i] - o.upper[i]) : 0.0;
    const double residual = p[i] - o.target[i] - o.bound_weight * below + o.bound_weight * above;
    const double weight = 1.0 + (below > 0.0 ? o.bound_weight : 0.0) + (above > 0.0 ? o.bound_weight : 0.0);
    a.gradient += w * g * residual;
    a.gauss_newton += w * g * g * weight;
    a.from_curve += w * 2.0 * sides.curve(i, j) * residual;
  }
  return a;
}

}  // namespace

// Coordinate descent: each side takes a Newton step of the objective along its parabola (a
// Gauss-Newton one where that is not convex), kept within its range, halved while it does not
// lower the error.
double interpolated_error(const LinearObjective& objective, const Eigen::VectorXd& values, const SideLight& sides,
                          Eigen::VectorXd* offsets) {
  const Eigen::Index m = sides.slope.cols();
  Eigen::VectorXd p = values, s = Eigen::VectorXd::Zero(m);
  double error = prediction_error(objective, p);
  auto moved_p = [&](Eigen::Index j, double to) {
    const double from = s[j];
    return Eigen::VectorXd(p + sides.slope.col(j) * (to - from) + sides.curve.col(j) * (to * to - from * from));
  };
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double largest = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      const AlongSide a = along_side(objective, p, sides, j, s[j]);
      double curvature = a.gauss_newton + a.from_curve;
      if (!(curvature > 0.0)) curvature = a.gauss_newton;
      if (!(curvature > 0.0)) continue;
      double to = std::clamp(s[j] - a.gradient / curvature, sides.low[j], sides.high[j]);
      for (int halving = 0; halving < 8 && to != s[j]; ++halving) {
        const Eigen::VectorXd q = moved_p(j, to);
        const double e = prediction_error(objective, q);
        if (e < error) {
          largest = std::max(largest, std::abs(to - s[j]));
          p = q, s[j] = to, error = e;
          break;
        }
        to = 0.5 * (to + s[j]);
      }
    }
    if (largest < kConverged) break;
  }
  if (offsets) *offsets = s;
  return error;
}

namespace {

GridRectangle on_grid(const PanelRectangle& r, double s) {
  return {r.panel, static_cast<int>(std::lround(r.v0 / s)), static_cast<int>(std::lround(r.v1 / s)) - 1,
          static_cast<int>(std::lround(r.u0 / s)), static_cast<int>(std::lround(r.u1 / s)) - 1};
}

double& side_edge(PanelRectangle& r, int side) { return side == 0 ? r.u0 : side == 1 ? r.u1 : side == 2 ? r.v0 : r.v1; }

}  // namespace

std::vector<PanelRectangle> interpolated_placement(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                                   const std::vector<PanelRectangle>& openings,
                                                   const PlacedValues& values_of, const LinearObjective& objective,
                                                   double* interpolated) {
  const double s = domain.element_size();
  const Eigen::VectorXd base = values_of(openings);
  std::vector<Eigen::VectorXd> out, in;
  std::vector<size_t> opening;
  std::vector<int> side_of;
  for (size_t i = 0; i < openings.size(); ++i) {
    if (!(domain.panels()[static_cast<size_t>(openings[i].panel)].thickness > 0.0f)) continue;
    const GridRectangle g = on_grid(openings[i], s);
    for (int side = 0; side < 4; ++side) {
      Eigen::VectorXd moved[2];
      for (int k = 0; k < 2; ++k) {
        const GridRectangle m = g.side_moved(side, k == 0 ? 1 : -1);
        if (!on_its_panel(domain, m)) continue;
        std::vector<PanelRectangle> changed = openings;
        changed[i] = panel_rectangle(m, s);
        moved[k] = values_of(changed) - base;
      }
      out.push_back(std::move(moved[0]));
      in.push_back(std::move(moved[1]));
      opening.push_back(i);
      side_of.push_back(side);
    }
  }
  if (interpolated) *interpolated = prediction_error(objective, base);
  if (opening.empty()) return openings;
  SideLight sides = side_light(out, in, opening, base.size());
  for (size_t j = 0; j < opening.size(); ++j) {
    const auto c = static_cast<Eigen::Index>(j);
    sides.high[c] = std::min(sides.high[c], side_reach(domain, constraints, openings, opening[j], side_of[j], true));
    sides.low[c] = std::max(sides.low[c], -side_reach(domain, constraints, openings, opening[j], side_of[j], false));
  }
  Eigen::VectorXd offsets;
  const double error = interpolated_error(objective, base, sides, &offsets);
  if (interpolated) *interpolated = error;
  std::vector<PanelRectangle> placed = openings;
  for (size_t j = 0; j < opening.size(); ++j) {
    double& edge = side_edge(placed[opening[j]], side_of[j]);
    const double outward = side_of[j] % 2 == 0 ? -1.0 : 1.0;
    const double to = edge + outward * offsets[static_cast<Eigen::Index>(j)] * s;
    double best = edge;
    for (float x : edge_positions(edge, s, constraints.module, true))
      if ((x - edge) * (to - edge) >= 0.0 && std::abs(x - edge) <= std::abs(to - edge) + 1e-9 &&
          std::abs(x - to) < std::abs(best - to))
        best = x;
    edge = best;
  }
  return constraint_violations(domain, placed, constraints).empty() ? placed : openings;
}

RefinableOpenings search_refinable_openings(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                            const std::vector<std::vector<GridRectangle>>& starts,
                                            const OpeningValues& values_of, const LinearObjective& objective,
                                            int max_evaluations, const Progress* progress, size_t descents) {
  Descent descent(domain, constraints, values_of, objective, max_evaluations, progress);
  return descent.run(starts, descents);
}

}  // namespace fenestra
