#include "solve/refinable_openings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "util/progress.h"

namespace fenestra {
namespace {

using Openings = std::vector<GridRectangle>;

// Coordinate sweeps of the interpolation's least squares, and the step (elements) that ends them.
constexpr int kMaxSweeps = 100;
constexpr double kConverged = 1e-5;
// A move smaller than this share of the error is no gain (rounding, not light).
constexpr double kRelativeGain = 1e-9;

bool well_formed(const GridRectangle& r) { return r.row0 <= r.row1 && r.col0 <= r.col1 && r.row0 >= 0 && r.col0 >= 0; }

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

  // The side light of `set` (a column per side move, less the set's values) and each column's
  // opening; false when the evaluations ran out.
  bool side_light(const Openings& set, const Eigen::VectorXd& base, Eigen::MatrixXd* sides,
                  std::vector<size_t>* owner) {
    std::vector<Eigen::VectorXd> columns;
    owner->clear();
    for (size_t i = 0; i < set.size(); ++i)
      for (int side = 0; side < 4; ++side)
        for (int step : {1, -1}) {
          Openings moved = set;
          moved[i] = set[i].side_moved(side, step);
          if (!well_formed(moved[i])) continue;
          const Eigen::VectorXd* v = values(moved);
          if (!v) return false;
          columns.push_back(*v - base);
          owner->push_back(i);
        }
    sides->resize(base.size(), static_cast<Eigen::Index>(columns.size()));
    for (size_t c = 0; c < columns.size(); ++c) sides->col(static_cast<Eigen::Index>(c)) = columns[c];
    return true;
  }

  // The interpolated error of `set`, from its own side light; nullopt when the evaluations ran out.
  std::optional<double> scored(const Openings& set, Eigen::MatrixXd* sides, std::vector<size_t>* owner) {
    const Eigen::VectorXd* base = values(set);
    if (!base) return std::nullopt;
    const Eigen::VectorXd copy = *base;  // side_light may grow the map (references stay, but be plain)
    if (!side_light(set, copy, sides, owner)) return std::nullopt;
    return interpolated_error(objective_, copy, *sides);
  }

  // Descent from the starts (within the constraints) whose interpolated errors are the
  // `descents` lowest, the lowest first; the best answer.
  RefinableOpenings run(const std::vector<Openings>& starts, size_t descents) {
    std::vector<std::pair<double, Openings>> ranked;
    std::vector<double> start_errors(starts.size(), std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < starts.size(); ++i) {
      const Openings& start = starts[i];
      if (start.empty() || !std::all_of(start.begin(), start.end(), well_formed) ||
          !satisfies_all(domain_, start, constraints_))
        continue;
      Eigen::MatrixXd sides;
      std::vector<size_t> owner;
      const std::optional<double> e = scored(start, &sides, &owner);
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
    Eigen::MatrixXd sides;
    std::vector<size_t> owner;
    const std::optional<double> first = scored(current, &sides, &owner);
    out.rects = current;
    out.error = std::numeric_limits<double>::infinity();
    if (!first) return out;
    out.start_error = out.error = *first;
    for (bool improved = true; improved;) {
      improved = false;
      for (const Neighbour& n : neighbours(current)) {
        if (!std::all_of(n.set.begin(), n.set.end(), well_formed) || !satisfies_all(domain_, n.set, constraints_))
          continue;
        const Eigen::VectorXd* v = values(n.set);
        if (!v) return out;
        // The screen: the neighbour's values with the current set's side light (less the removed
        // opening's); only a neighbour it finds better is scored with its own.
        if (!(screened(*v, sides, owner, n) < out.error * (1.0 - kRelativeGain))) continue;
        Eigen::MatrixXd its_sides;
        std::vector<size_t> its_owner;
        const std::optional<double> e = scored(n.set, &its_sides, &its_owner);
        if (!e) return out;
        if (!(*e < out.error * (1.0 - kRelativeGain))) continue;
        current = n.set;
        sides = std::move(its_sides);
        owner = std::move(its_owner);
        out.rects = sorted(current);
        out.error = *e;
        ++out.moves;
        improved = true;
        break;
      }
    }
    return out;
  }

  double screened(const Eigen::VectorXd& values, const Eigen::MatrixXd& sides, const std::vector<size_t>& owner,
                  const Neighbour& n) const {
    if (!n.removed) return interpolated_error(objective_, values, sides);
    std::vector<Eigen::Index> kept;
    for (size_t c = 0; c < owner.size(); ++c)
      if (owner[c] != n.opening) kept.push_back(static_cast<Eigen::Index>(c));
    Eigen::MatrixXd fewer(sides.rows(), static_cast<Eigen::Index>(kept.size()));
    for (size_t c = 0; c < kept.size(); ++c) fewer.col(static_cast<Eigen::Index>(c)) = sides.col(kept[c]);
    return interpolated_error(objective_, values, fewer);
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

// Coordinate descent on the objective, a convex piecewise quadratic in t: each coordinate takes the
// Newton step of its own quadratic (the bounds' penalties where they are active), kept in the box.
double interpolated_error(const LinearObjective& objective, const Eigen::VectorXd& values,
                          const Eigen::MatrixXd& sides, double reach) {
  Eigen::VectorXd p = values;
  Eigen::VectorXd t = Eigen::VectorXd::Zero(sides.cols());
  const bool lower = objective.lower.size() > 0, upper = objective.upper.size() > 0;
  const double bw = objective.bound_weight;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double largest = 0.0;
    for (Eigen::Index j = 0; j < sides.cols(); ++j) {
      double gradient = 0.0, curvature = 0.0;
      for (Eigen::Index i = 0; i < p.size(); ++i) {
        const double w = objective.weight[i], a = sides(i, j);
        if (!(w > 0.0) || a == 0.0) continue;
        const double below = lower ? std::max(0.0, objective.lower[i] - p[i]) : 0.0;
        const double above = upper ? std::max(0.0, p[i] - objective.upper[i]) : 0.0;
        gradient += w * a * (p[i] - objective.target[i] - bw * below + bw * above);
        curvature += w * a * a * (1.0 + (below > 0.0 ? bw : 0.0) + (above > 0.0 ? bw : 0.0));
      }
      if (!(curvature > 0.0)) continue;
      const double next = std::clamp(t[j] - gradient / curvature, 0.0, reach);
      const double step = next - t[j];
      if (step == 0.0) continue;
      p += step * sides.col(j);
      t[j] = next;
      largest = std::max(largest, std::abs(step));
    }
    if (largest < kConverged) break;
  }
  return prediction_error(objective, p);
}

RefinableOpenings search_refinable_openings(const OpeningDomain& domain, const OpeningConstraints& constraints,
                                            const std::vector<std::vector<GridRectangle>>& starts,
                                            const OpeningValues& values_of, const LinearObjective& objective,
                                            int max_evaluations, const Progress* progress, size_t descents) {
  Descent descent(domain, constraints, values_of, objective, max_evaluations, progress);
  return descent.run(starts, descents);
}

}  // namespace fenestra
