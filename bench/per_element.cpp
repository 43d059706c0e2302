#include "per_element.h"

#include <cstdio>

#include "trace/evaluate.h"
#include "trace/ray_scene.h"

namespace bench {

namespace {

struct Evaluation {
  VectorXd value;
  double seconds = 0.0;
  uint64_t rays = 0;
};

Evaluation timed_evaluate(const Scene& scene, const std::vector<fenestra::Rectangle>& openings) {
  const uint64_t rays_before = fenestra::rays_traced();
  const auto start = Clock::now();
  Evaluation e;
  e.value = fenestra::evaluate_openings(scene, {openings.begin(), openings.end()}).value;
  e.seconds = seconds_since(start);
  e.rays = fenestra::rays_traced() - rays_before;
  return e;
}

// Column k = evaluate({element k}) - evaluate({}). Every run shares the seed, so paths stay identical
// until they reach the opened element (common random numbers): this favours the baseline.
BaselineRung measure_baseline(const Scene& base, int paths, const std::vector<int>& columns, const MatrixXd& ref_columns) {
  const Scene scene = with_paths(base, paths, kBaselineSeed);
  BaselineRung r;
  r.paths = paths;
  const Evaluation closed = timed_evaluate(scene, {});
  r.closed_seconds = closed.seconds;
  r.rays = closed.rays;
  MatrixXd estimate(ref_columns.rows(), ref_columns.cols());
  for (size_t j = 0; j < columns.size(); ++j) {
    const Evaluation open = timed_evaluate(scene, {scene.domain.elements()[columns[j]].corners});
    estimate.col(static_cast<Eigen::Index>(j)) = open.value - closed.value;
    r.columns_seconds += open.seconds;
    r.rays += open.rays;
  }
  r.subset = relative_frobenius(estimate, ref_columns);
  return r;
}

void print_baseline_header() {
  std::printf("  %7s %9s %9s %8s %9s %13s\n", "paths", "closed s", "8 cols s", "Mrays/s", "err 8col", "all cols s");
}

void print_baseline_rung(const BaselineRung& r, size_t elements) {
  const double seconds = r.closed_seconds + r.columns_seconds;
  std::printf("  %7d %9.3f %9.3f %8.2f %9.4f %13.1f%s\n", r.paths, r.closed_seconds, r.columns_seconds,
              r.rays * 1e-6 / seconds, r.subset, r.total_seconds(elements),
              r.subset <= kFrobeniusTarget ? "  <- 2% met" : "");
  std::fflush(stdout);
}

// The one-pass rung that first matches the baseline's reached error on the same columns, or null.
const Rung* matching_rung(const std::vector<Rung>& ladder, double subset_error) {
  for (const Rung& r : ladder)
    if (r.subset <= subset_error) return &r;
  return nullptr;
}

}  // namespace

std::vector<int> baseline_columns(size_t elements) {
  std::vector<int> columns;
  for (int i = 0; i < kBaselineColumns; ++i) columns.push_back(static_cast<int>(i * elements / kBaselineColumns));
  return columns;
}

std::vector<BaselineRung> baseline_ladder(const Scene& scene, int top, const std::vector<int>& columns,
                                          const Reference& ref) {
  const MatrixXd ref_columns = take_columns(ref.E, columns);
  const size_t elements = scene.domain.element_count();
  std::vector<BaselineRung> ladder;
  print_baseline_header();
  for (int paths = kFirstRung; paths <= top; paths *= 2) {
    ladder.push_back(measure_baseline(scene, paths, columns, ref_columns));
    print_baseline_rung(ladder.back(), elements);
    if (ladder.back().subset <= kFrobeniusTarget) break;
  }
  return ladder;
}

json baseline_rung_json(const BaselineRung& r, size_t elements) {
  return {{"paths", r.paths},
          {"closed_seconds", r.closed_seconds},
          {"columns_seconds", r.columns_seconds},
          {"rays", r.rays},
          {"relative_frobenius_error", r.subset},
          {"all_columns_seconds", r.total_seconds(elements)}};
}

json target_ratio_json(const std::vector<BaselineRung>& baseline, const TimeToAccuracy& one_pass, size_t elements) {
  const BaselineRung& last = baseline.back();
  const double spent = last.total_seconds(elements);
  const bool reached = last.subset <= kFrobeniusTarget;
  const double needed = reached ? spent : spent * path_factor(last.subset, kFrobeniusTarget);
  return {{"baseline_reached_target", reached},
          {"one_pass_measured", one_pass.measured},
          {"baseline_error_reached", last.subset},
          {"baseline_all_columns_seconds", needed},
          {"ratio", needed / one_pass.seconds},
          {"ratio_lower_bound", spent / one_pass.seconds}};
}

void print_target_ratio(const json& r) {
  const bool measured = r["baseline_reached_target"].get<bool>() && r["one_pass_measured"].get<bool>();
  const char* one_pass = r["one_pass_measured"].get<bool>() ? "measured" : "EXTRAPOLATED";
  if (measured) {
    std::printf("    ratio at the 2%% target (measured): t_per_element_total / t_one_pass = %.1f\n",
                r["ratio"].get<double>());
    return;
  }
  if (!r["baseline_reached_target"].get<bool>())
    std::printf("    The per-element approach did NOT reach 2%% within the budget (reached %.4f).\n",
                r["baseline_error_reached"].get<double>());
  std::printf("    ratio at the 2%% target, one-pass time %s:\n", one_pass);
  std::printf("      LOWER BOUND (per-element time already spent, all No columns / one-pass time): >= %.1f\n",
              r["ratio_lower_bound"].get<double>());
  std::printf("      EXTRAPOLATED (both at 2%%, errors ~ 1/sqrt(paths)):                          ~ %.1f\n",
              r["ratio"].get<double>());
}

json matched_ratio_json(const std::vector<BaselineRung>& baseline, const std::vector<Rung>& ladder, size_t elements) {
  const BaselineRung& last = baseline.back();
  const Rung* match = matching_rung(ladder, last.subset);
  if (!match) return {{"available", false}};
  return {{"available", true},
          {"baseline_paths", last.paths},
          {"baseline_error", last.subset},
          {"baseline_all_columns_seconds", last.total_seconds(elements)},
          {"one_pass_paths", match->paths},
          {"one_pass_error", match->subset},
          {"one_pass_seconds", match->seconds},
          {"ratio", last.total_seconds(elements) / match->seconds}};
}

void print_matched_ratio(const json& m) {
  if (!m["available"].get<bool>()) {
    std::printf("    ratio at matched accuracy: no one-pass rung was as accurate on these columns\n");
    return;
  }
  std::printf("    ratio at matched accuracy (measured, same %d columns, one-pass error <= baseline error):\n"
              "      per-element %d paths: error %.4f, %.1f s for all columns; one-pass %d paths: error %.4f,\n"
              "      %.3f s  =>  t_per_element_total / t_one_pass = %.1f\n",
              kBaselineColumns, m["baseline_paths"].get<int>(), m["baseline_error"].get<double>(),
              m["baseline_all_columns_seconds"].get<double>(), m["one_pass_paths"].get<int>(),
              m["one_pass_error"].get<double>(), m["one_pass_seconds"].get<double>(), m["ratio"].get<double>());
}

}  // namespace bench
