#include "solve/prediction_check.h"

#include <cmath>
#include <cstdio>

#include "trace/path_tracer.h"

namespace fenestra {

std::string sparse_sampling_warning(int paths_per_sensor, size_t elements) {
  const double samples = static_cast<double>(paths_per_sensor) * PathTracer::kSensorPortals;
  if (elements == 0 || samples >= static_cast<double>(elements)) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "%d paths per sensor send %.0f direct samples for %zu elements: each element's contribution is "
                "unbiased but rests on %.2f samples per sensor, so the predicted values are noisy; use at least "
                "%zu paths per sensor (or larger elements) for a dependable solve",
                paths_per_sensor, samples, elements, samples / static_cast<double>(elements),
                (elements + PathTracer::kSensorPortals - 1) / PathTracer::kSensorPortals);
  return text;
}

std::string prediction_mismatch_warning(const SolveResult& r) {
  if (!r.verified || r.predicted.size() == 0) return "";
  double chi2 = 0.0, z_sum = 0.0, diff2 = 0.0, pred2 = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < r.predicted.size(); ++i) {
    const double d = r.verified_value[i] - r.predicted[i];
    const double var = r.predicted_stderr[i] * r.predicted_stderr[i] + r.verified_stderr[i] * r.verified_stderr[i];
    diff2 += d * d;
    pred2 += r.predicted[i] * r.predicted[i];
    if (!std::isfinite(var)) continue;  // an unknown error (one path) tests nothing
    chi2 += var > 0.0 ? d * d / var : (d != 0.0 ? INFINITY : 0.0);
    z_sum += var > 0.0 ? d / std::sqrt(var) : 0.0;
    ++n;
  }
  const double rms = pred2 > 0.0 ? std::sqrt(diff2 / pred2) : (diff2 > 0.0 ? INFINITY : 0.0);
  // Sensors' paths are independent, so without a bias the z-scores are too: their mean square
  // tests the spread, their sum a shift to one side (a solver that chose noise that flattered it).
  const bool beyond_errors = n > 0 && (chi2 / n > 1.0 + 4.0 * std::sqrt(2.0 / n) ||
                             std::abs(z_sum) / std::sqrt(static_cast<double>(n)) > 3.5);
  if (!beyond_errors || !(rms > 0.01)) return "";
  char text[520];
  std::snprintf(text, sizeof text,
                "the openings checked with real cutters give %.1f%% relative RMS error against the goals, the "
                "prediction %.1f%%; the values differ by %.1f%% RMS, beyond their standard errors: trust the checked "
                "figure. More paths per sensor help when they are few for the elements; otherwise the building "
                "differs from what the estimate models (e.g. the reveals of thick walls)",
                100.0 * r.verified_error.relative_rms, 100.0 * r.error.relative_rms, 100.0 * rms);
  return text;
}

}  // namespace fenestra
