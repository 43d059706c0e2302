#include "solve/thick_wall_joint_edges.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Dense>

#include "solve/cut_region_search.h"
#include "solve/thick_wall_edges.h"
#include "util/progress.h"

namespace fenestra {
namespace {

struct Side {
  size_t opening;
  int which;  // 0: u0, 1: u1, 2: v0, 3: v1
};

double& side_of(PanelRectangle& r, int which) {
  return which == 0 ? r.u0 : which == 1 ? r.u1 : which == 2 ? r.v0 : r.v1;
}

// The objective's error as a sum of squares (r'r == prediction_error(objective, net)): the
// weighted misses of the targets, then of the lower and of the upper bounds.
Eigen::VectorXd residuals(const LinearObjective& o, const Eigen::VectorXd& net) {
  const Eigen::Index n = net.size();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = std::sqrt(o.weight[i]), wb = w * std::sqrt(o.bound_weight);
    r[i] = w * (net[i] - o.target[i]);
    if (o.lower.size()) r[n + i] = wb * std::max(0.0, o.lower[i] - net[i]);
    if (o.upper.size()) r[2 * n + i] = wb * std::max(0.0, net[i] - o.upper[i]);
  }
  return r;
}

// d residuals / d sides from d values / d sides (the bounds' rows where they are missed).
Eigen::MatrixXd residual_jacobian(const LinearObjective& o, const Eigen::VectorXd& net, const Eigen::MatrixXd& dv) {
  const Eigen::Index n = net.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3 * n, dv.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = std::sqrt(o.weight[i]), wb = w * std::sqrt(o.bound_weight);
    J.row(i) = w * dv.row(i);
    if (o.lower.size() && o.lower[i] > net[i]) J.row(n + i) = -wb * dv.row(i);
    if (o.upper.size() && net[i] > o.upper[i]) J.row(2 * n + i) = wb * dv.row(i);
  }
  return J;
}

class JointEdgeSearch {
 public:
  JointEdgeSearch(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                  const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start, int paths,
                  int judge_paths, uint64_t stream, Progress* progress)
      : domain_(domain), records_(records), objective_(objective), constraints_(constraints), paths_(paths),
        judge_paths_(judge_paths), stream_(stream), progress_(progress),
        closed_(records.contributions().closed.value),
        violations_(constraint_violations(domain, start, constraints).size()) {
    for (size_t i = 0; i < start.size(); ++i)
      if (domain.panels()[static_cast<size_t>(start[i].panel)].thickness > 0.0f)
        for (int which = 0; which < 4; ++which) sides_.push_back({i, which});
    const std::vector<double> steps = edge_steps(domain.element_size(), constraints.module, true);
    h_ = steps.back();
    unit_ = constraints.module > 0.0 ? constraints.module : kContinuousEdgeStep;
    span_ = thick_wall_edge_span(domain.element_size(), constraints.module);
  }

  ThickWallJointEdges run(const std::vector<PanelRectangle>& start) {
    ThickWallJointEdges out;
    out.openings = start;
    out.sides = static_cast<int>(sides_.size());
    out.start_values = out.values = judged(start, &out);
    double error = prediction_error(objective_, out.values.value - closed_);
    while (!sides_.empty() && out.steps < kJointEdgeMaxSteps) {
      const Eigen::MatrixXd dv = value_differences(out.openings, &out);
      const Eigen::VectorXd net = out.values.value - closed_;
      const Eigen::MatrixXd J = residual_jacobian(objective_, net, dv);
      const Eigen::VectorXd r = residuals(objective_, net);
      const Eigen::MatrixXd A = J.transpose() * J;
      const double scale = A.diagonal().mean();
      if (!(scale > 0.0)) break;
      const Eigen::VectorXd g = J.transpose() * r;
      std::optional<std::pair<std::vector<PanelRectangle>, SensorValues>> best;
      double best_error = error;
      std::vector<std::vector<PanelRectangle>> tried;  // dampings that snap to the same openings are judged once
      for (double damping : kJointEdgeDampings) {
        const std::optional<std::vector<PanelRectangle>> moved = admissible_step(out.openings, A, g, damping * scale);
        if (!moved || std::find(tried.begin(), tried.end(), *moved) != tried.end()) continue;
        tried.push_back(*moved);
        const SensorValues v = judged(*moved, &out);
        const double e = prediction_error(objective_, v.value - closed_);
        if (e < best_error) best_error = e, best = std::make_pair(*moved, v);
      }
      if (!best || !(std::sqrt(best_error) < (1.0 - kJointEdgeGain) * std::sqrt(error))) break;
      out.openings = std::move(best->first);
      out.values = std::move(best->second);
      error = best_error;
      ++out.steps;
    }
    return out;
  }

 private:
  bool within_constraints(const std::vector<PanelRectangle>& openings) const {
    return constraint_violations(domain_, openings, constraints_).size() <= violations_;
  }

  std::vector<PanelRectangle> moved(std::vector<PanelRectangle> openings, size_t k, double by) const {
    side_of(openings[sides_[k].opening], sides_[k].which) += by;
    return openings;
  }

  SensorValues cut(const std::vector<PanelRectangle>& openings, int paths) {
    if (progress_) progress_->throw_if_cancelled();
    return records_.cut(std::vector<OpeningInput>(openings.begin(), openings.end()), paths, stream_);
  }

  SensorValues judged(const std::vector<PanelRectangle>& openings, ThickWallJointEdges* out) {
    ++out->judged_cuts;
    return cut(openings, judge_paths_);
  }

  // Sensors x sides: each side's effect per meter, by central differences of +-h (one-sided where
  // the side cannot move one way; zero where it can move neither). A side's differences are cut
  // at the sensors its moves can reach (RecordQueries::sensors_reached); at the others they are 0
  // (the same paths).
  Eigen::MatrixXd value_differences(const std::vector<PanelRectangle>& openings, ThickWallJointEdges* out) {
    Eigen::MatrixXd dv = Eigen::MatrixXd::Zero(closed_.size(), static_cast<Eigen::Index>(sides_.size()));
    std::optional<Eigen::VectorXd> here;  // the openings' own cut at `paths_`, for one-sided ones
    for (size_t k = 0; k < sides_.size(); ++k) {
      const std::vector<PanelRectangle> up = moved(openings, k, h_), down = moved(openings, k, -h_);
      const bool can_up = within_constraints(up), can_down = within_constraints(down);
      if (!can_up && !can_down) continue;
      std::vector<size_t> reached = records_.sensors_reached(openings, up);
      for (size_t i : records_.sensors_reached(openings, down)) reached.push_back(i);
      std::sort(reached.begin(), reached.end());
      reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
      if (reached.empty()) continue;
      if (!(can_up && can_down) && !here) here = counted_cut(openings, {}, out);
      const Eigen::VectorXd high = can_up ? counted_cut(up, reached, out) : picked(*here, reached);
      const Eigen::VectorXd low = can_down ? counted_cut(down, reached, out) : picked(*here, reached);
      const Eigen::VectorXd d = (high - low) / ((can_up && can_down ? 2.0 : 1.0) * h_);
      for (size_t i = 0; i < reached.size(); ++i)
        dv(static_cast<Eigen::Index>(reached[i]), static_cast<Eigen::Index>(k)) = d[static_cast<Eigen::Index>(i)];
    }
    return dv;
  }

  // The openings cut at the sensors `at` (empty: every sensor, in order).
  Eigen::VectorXd counted_cut(const std::vector<PanelRectangle>& openings, const std::vector<size_t>& at,
                              ThickWallJointEdges* out) {
    ++out->cuts;
    if (progress_) progress_->throw_if_cancelled();
    out->sensors_cut += static_cast<size_t>(closed_.size());
    out->sensors_traced += at.empty() ? static_cast<size_t>(closed_.size()) : at.size();
    const std::vector<OpeningInput> inputs(openings.begin(), openings.end());
    return at.empty() ? records_.cut(inputs, paths_, stream_).value : records_.cut_at(inputs, paths_, stream_, at).value;
  }

  static Eigen::VectorXd picked(const Eigen::VectorXd& all, const std::vector<size_t>& at) {
    Eigen::VectorXd out(static_cast<Eigen::Index>(at.size()));
    for (size_t i = 0; i < at.size(); ++i) out[static_cast<Eigen::Index>(i)] = all[static_cast<Eigen::Index>(at[i])];
    return out;
  }

  // The damped step from `openings` (A = J'J, g = J'r), with the sides of every opening it would
  // make inadmissible (too small, off the elements, too near another) held where they are and the
  // others solved again; nullopt when nothing moves.
  std::optional<std::vector<PanelRectangle>> admissible_step(const std::vector<PanelRectangle>& openings,
                                                             const Eigen::MatrixXd& A, const Eigen::VectorXd& g,
                                                             double damping) const {
    std::vector<uint8_t> held(sides_.size(), 0);
    for (size_t round = 0; round <= openings.size(); ++round) {
      Eigen::MatrixXd damped = A;
      damped.diagonal().array() += damping;
      Eigen::VectorXd rhs = -g;
      for (size_t k = 0; k < sides_.size(); ++k) {
        if (!held[k]) continue;
        const auto e = static_cast<Eigen::Index>(k);
        damped.row(e).setZero();
        damped.col(e).setZero();
        damped(e, e) = 1.0;
        rhs[e] = 0.0;
      }
      const std::optional<std::vector<PanelRectangle>> out = stepped(openings, damped.ldlt().solve(rhs));
      if (!out) return std::nullopt;
      const std::vector<size_t> broken = newly_inadmissible(openings, *out);
      if (broken.empty()) return within_constraints(*out) ? out : std::nullopt;
      for (size_t k = 0; k < sides_.size(); ++k)
        if (std::find(broken.begin(), broken.end(), sides_[k].opening) != broken.end()) held[k] = 1;
    }
    return std::nullopt;
  }

  // The openings moved by `d`, each side clipped to the span and snapped to the unit; nullopt
  // when nothing moves.
  std::optional<std::vector<PanelRectangle>> stepped(const std::vector<PanelRectangle>& openings,
                                                     const Eigen::VectorXd& d) const {
    std::vector<PanelRectangle> out = openings;
    bool any = false;
    for (size_t k = 0; k < sides_.size(); ++k) {
      double& side = side_of(out[sides_[k].opening], sides_[k].which);
      const double to = unit_ * std::round((side + std::clamp(d[static_cast<Eigen::Index>(k)], -span_, span_)) / unit_);
      if (std::abs(to - side) < 0.5 * unit_) continue;
      side = to;
      any = true;
    }
    if (!any) return std::nullopt;
    return out;
  }

  // The openings `after` makes inadmissible, alone or beside another of their panel, that were not.
  std::vector<size_t> newly_inadmissible(const std::vector<PanelRectangle>& before,
                                         const std::vector<PanelRectangle>& after) const {
    std::vector<size_t> out;
    for (size_t i = 0; i < after.size(); ++i) {
      bool broken = !admissible(after[i], domain_, constraints_) && admissible(before[i], domain_, constraints_);
      for (size_t j = 0; j < after.size() && !broken; ++j)
        broken = j != i && after[j].panel == after[i].panel && !apart(after[i], after[j], constraints_) &&
                 apart(before[i], before[j], constraints_);
      if (broken) out.push_back(i);
    }
    return out;
  }

  const OpeningDomain& domain_;
  RecordQueries& records_;
  const LinearObjective& objective_;
  const OpeningConstraints& constraints_;
  const int paths_, judge_paths_;
  const uint64_t stream_;
  Progress* progress_;
  const Eigen::VectorXd closed_;
  const size_t violations_;  // the start's: a step may not add any
  std::vector<Side> sides_;
  double h_ = 0.0, unit_ = 0.0, span_ = 0.0;
};

}  // namespace

ThickWallJointEdges joint_thick_wall_edges(const OpeningDomain& domain, RecordQueries& records,
                                           const LinearObjective& objective, const OpeningConstraints& constraints,
                                           const std::vector<PanelRectangle>& start, int paths, int judge_paths,
                                           uint64_t stream, Progress* progress) {
  return JointEdgeSearch(domain, records, objective, constraints, start, paths, judge_paths, stream, progress)
      .run(start);
}

void scan_stalled_joint_edges(const OpeningDomain& domain, RecordQueries& records, const LinearObjective& objective,
                              const OpeningConstraints& constraints, const std::vector<PanelRectangle>& start,
                              int paths, int judge_paths, uint64_t stream, Progress* progress,
                              ThickWallJointEdges* joint) {
  const Eigen::VectorXd& closed = records.contributions().closed.value;
  CutRegionSearch search(records, start, paths, kThickWallEdgeCutStream);
  const EdgeRefinement scanned =
      refine_edges(domain, closed, objective, constraints, &search, progress, thick_wall_edge_scope(domain, constraints));
  joint->scanned = true;
  joint->scan_cuts = search.cuts();
  joint->scan_rough_cuts = search.rough_cuts();
  joint->sensors_traced += search.sensors_traced();
  joint->sensors_cut += search.sensors_cut();
  if (scanned.moves == 0) return;
  if (progress) progress->throw_if_cancelled();
  const SensorValues judged = records.cut(std::vector<OpeningInput>(scanned.openings.begin(), scanned.openings.end()),
                                          judge_paths, stream);
  ++joint->judged_cuts;
  if (!(prediction_error(objective, judged.value - closed) < prediction_error(objective, joint->values.value - closed)))
    return;
  joint->openings = scanned.openings;
  joint->values = judged;
  joint->scan_moves = scanned.moves;
}

}  // namespace fenestra
