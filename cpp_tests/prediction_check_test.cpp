// The solve's own warnings: too few paths for the elements, and a prediction the real-cutter
// check contradicts beyond the standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "solve/prediction_check.h"

namespace fenestra {
namespace {

SolveResult result_with(const std::vector<double>& predicted, const std::vector<double>& verified, double stderr_) {
  SolveResult r;
  const Eigen::Index n = static_cast<Eigen::Index>(predicted.size());
  r.predicted = Eigen::Map<const Eigen::VectorXd>(predicted.data(), n);
  r.verified_value = Eigen::Map<const Eigen::VectorXd>(verified.data(), n);
  r.predicted_stderr = Eigen::VectorXd::Constant(n, stderr_);
  r.verified_stderr = Eigen::VectorXd::Constant(n, stderr_);
  r.verified = true;
  return r;
}

TEST(PredictionCheck, FewerDirectSamplesThanElementsWarns) {
  EXPECT_NE(sparse_sampling_warning(64, 1080).find("256 direct samples for 1080 elements"), std::string::npos);
  EXPECT_NE(sparse_sampling_warning(64, 1080).find("at least 270 paths"), std::string::npos);
  EXPECT_EQ(sparse_sampling_warning(270, 1080), "");
  EXPECT_EQ(sparse_sampling_warning(4096, 200), "");
}

TEST(PredictionCheck, AgreementWithinTheErrorsIsQuiet) {
  // Differences of about one standard error, both signs.
  std::vector<double> p(16, 1000.0), v(16);
  for (int i = 0; i < 16; ++i) v[i] = 1000.0 + (i % 2 ? 14.0 : -14.0);
  EXPECT_EQ(prediction_mismatch_warning(result_with(p, v, 10.0)), "");
}

TEST(PredictionCheck, SpreadBeyondTheErrorsWarns) {
  std::vector<double> p(16, 1000.0), v(16);
  for (int i = 0; i < 16; ++i) v[i] = 1000.0 + (i % 2 ? 60.0 : -60.0);  // 4 combined standard errors
  EXPECT_NE(prediction_mismatch_warning(result_with(p, v, 10.0)).find("beyond their standard errors"),
            std::string::npos);
}

TEST(PredictionCheck, ShiftToOneSideWarnsEvenWhenEachSensorIsWithinItsError) {
  // Every sensor 1.1 combined standard errors low: mean square 1.2 passes, the sum (4.4 sigma) does not.
  std::vector<double> p(16, 1000.0), v(16, 1000.0 - 1.1 * std::sqrt(2.0) * 10.0);
  EXPECT_NE(prediction_mismatch_warning(result_with(p, v, 10.0)), "");
}

TEST(PredictionCheck, TinyDifferencesAreNotWorthAWarning) {
  // Far beyond vanishing standard errors, but 0.5 % of the values: below the 1 % floor.
  std::vector<double> p(16, 1000.0), v(16, 1005.0);
  EXPECT_EQ(prediction_mismatch_warning(result_with(p, v, 0.01)), "");
}

TEST(PredictionCheck, UnverifiedOrUnknownErrorsTestNothing) {
  SolveResult r = result_with({1000.0}, {2000.0}, 10.0);
  r.verified = false;
  EXPECT_EQ(prediction_mismatch_warning(r), "");
  r.verified = true;  // one path: no spread to compare with
  r.predicted_stderr[0] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(prediction_mismatch_warning(r), "");
}

}  // namespace
}  // namespace fenestra
