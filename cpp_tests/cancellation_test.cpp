// The transport matrix T built in place and block by block (trace/transport_matrix.h) is the
// matrix built before, to the bit; every long stage stops soon after a cancel; the cost model's
// refusal for too many elements names an element size that fits.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <thread>

#include "annual/annual_contributions.h"
#include "scene/element_size_hint.h"
#include "solve/nnls.h"
#include "study/cost_model.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/transport_matrix.h"

using namespace fenestra;
using namespace fenestra::test;

namespace {

Scene grey_room(const TempDir& dir, double element_size, int paths) {
  ObjBuilder obj;
  obj.box({0, 0, 0}, {3, 3, 2.5f}, [](const std::string& f) { return f == "south" ? "facade" : "grey"; });
  dir.write("scene.obj", obj.str());
  std::ostringstream s;
  s << R"({"fenestra": 1, "geometry": "scene.obj", "materials": {"grey": {"reflectance": 0.7}, "facade": {"reflectance": 0.5}},)"
    << R"( "opening_domain": {"materials": ["facade"], "element_size": )" << element_size << "},"
    << R"( "sensors": {"points": [[1.5, 1, 0.8], [0.5, 2.5, 0.8], [2.5, 0.5, 1.2]], "normals": [0, 0, 1]},)"
    << R"( "sky": {"type": "uniform", "radiance": 100}, "render": {"paths_per_sensor": )" << paths << "}}";
  dir.write("scene.json", s.str());
  return load_scene(dir.file("scene.json"));
}

// T as it was built before: accumulated in a zeroed matrix, then (S + S^T) / (paths x sensors).
Eigen::MatrixXd transport_as_before(const Contributions& c) {
  const Eigen::Index n = static_cast<Eigen::Index>(c.element_count());
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
  for (const SensorRecord& rec : c.records)
    for (size_t p = 0; p < rec.path_count(); ++p)
      for (uint32_t j = rec.path_begin[p]; j < rec.path_begin[p + 1]; ++j) {
        if (!rec.events[j].is_escape()) continue;
        for (uint32_t l = j + 1; l < rec.path_begin[p + 1]; ++l)
          if (!rec.events[l].is_light() && rec.events[l].element() != rec.events[j].element())
            S(rec.events[j].element(), rec.events[l].element()) += rec.events[l].value();
      }
  return (S + S.transpose()).eval() / static_cast<double>(static_cast<size_t>(c.paths_per_sensor) * c.records.size());
}

// Runs work(progress) on a thread, cancels `after` seconds in; the seconds from the cancel to its end.
template <typename Work>
double cancel_after(double after, Work work) {
  Progress progress;
  std::chrono::steady_clock::time_point end;
  bool cancelled = false;
  std::thread thread([&] {
    try {
      work(&progress);
    } catch (const Cancelled&) {
      cancelled = true;
    }
    end = std::chrono::steady_clock::now();
  });
  std::this_thread::sleep_for(std::chrono::duration<double>(after));
  const auto at = std::chrono::steady_clock::now();
  progress.cancel();
  thread.join();
  EXPECT_TRUE(cancelled) << "ended before the cancel: make the work longer";
  return std::chrono::duration<double>(end - at).count();
}

}  // namespace

TEST(TransportMatrix, EqualsTheMatrixBuiltBeforeToTheBit) {
  TempDir dir;
  for (double size : {0.5, 0.1}) {  // 30 elements, and 750 (several blocks, a partial last one)
    const Scene scene = grey_room(dir, size, 2048);
    const Contributions c = compute_contributions(scene);
    const Eigen::MatrixXd before = transport_as_before(c);
    ASSERT_EQ(c.T.rows(), before.rows());
    EXPECT_GT(c.T.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((c.T.array() != before.array()).count(), 0) << size;
    EXPECT_TRUE(c.T.isApprox(c.T.transpose(), 0.0));
  }
}

TEST(TransportMatrix, StopsSoonAfterACancelWhateverItsSize) {
  TempDir dir;
  const Scene scene = grey_room(dir, 0.025, 256);  // 12 000 elements: T is 1.15 GB
  Contributions c = compute_contributions(grey_room(dir, 0.5, 256));
  c.records.resize(3);
  const double latency = cancel_after(0.3, [&](Progress* p) {
    transport_matrix(c.records, scene.domain.element_count(), 256, 0, p);
  });
  EXPECT_LT(latency, 0.5);
  std::cout << "transport matrix of 12 000 elements: stopped " << latency << " s after the cancel\n";
}

TEST(Cancellation, NnlsStopsSoon) {
  // 400 x 20 000 with a solution of 300 positive entries: hundreds of iterations of 8 million
  // multiply-adds each (seconds).
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(400, 20000, [&] { return g(rng); });
  Eigen::VectorXd x = Eigen::VectorXd::Zero(20000);
  for (int k = 0; k < 300; ++k) x[k * 61] = 1.0 + std::abs(g(rng));
  const Eigen::VectorXd b = A * x;
  const double latency = cancel_after(0.3, [&](Progress* p) { nnls(A, b, 0, 0.0, p); });
  EXPECT_LT(latency, 0.5);
  std::cout << "NNLS 400 x 20 000: stopped " << latency << " s after the cancel\n";
}

TEST(ElementSizeHint, TheSmallestTypedSizeThatFits) {
  // 47 500 elements at 0.04 m; 16 bytes per element squared must fit in 19.3 GB.
  const auto bytes = [](double n) { return 16.0 * n * n; };
  const double fits = element_size_that_fits(0.04, 47500, bytes, 19.3e9, 1e6);
  EXPECT_NEAR(fits, 0.05, 1e-12);
  const double elements = 47500 * (0.04 / fits) * (0.04 / fits);
  EXPECT_LE(bytes(elements), 19.3e9);
  EXPECT_GT(bytes(47500 * (0.04 / 0.046) * (0.04 / 0.046)), 19.3e9);  // exact: 0.0468 m
  // 7 906 elements fit in 1 GB: 0.889 m is exact, in 5 cm steps from 0.2 m; 11.25 m in 10 cm steps.
  EXPECT_NEAR(element_size_that_fits(0.25, 1e5, bytes, 1e9, 1e6), 0.9, 1e-12);
  EXPECT_NEAR(element_size_that_fits(0.5, 4e6, bytes, 1e9, 1e6), 11.3, 1e-12);
  // The count alone: a million elements at most, exactly 0.01 m here.
  EXPECT_NEAR(element_size_that_fits(0.001, 1e8, [](double) { return 0.0; }, 1.0, 1e6), 0.01, 1e-12);
  EXPECT_EQ(element_size_that_fits(0.1, 100, bytes, 1.0, 1e6), 0.0);  // not even one element
  EXPECT_EQ(element_size_that_fits(0.1, 100, bytes, 1e9, 1e6), 0.1);  // fits already
  EXPECT_EQ(larger_element_size(0.05),
            "a larger element_size (0.05 m or more: opening_domain.element_size or solver.element_size)");
  EXPECT_EQ(larger_element_size(0.0), kLargerElementSize);
}

TEST(ElementSizeHint, TheRefusalNamesASizeThatTheCostModelAccepts) {
  TempDir dir;
  const Scene fine = grey_room(dir, 0.05, 256);  // 3 000 elements: T 72 MB
  const MemoryLimit limit{40000000, "in the test"};
  try {
    check_cost(fine, CostCommand::Solve, limit);
    FAIL() << "not refused";
  } catch (const CostError& e) {
    const std::string message = e.what();
    const size_t at = message.find(" m or more");
    ASSERT_NE(at, std::string::npos) << message;
    const double size = std::stod(message.substr(message.rfind('(', at) + 1));
    EXPECT_GT(size, 0.05);
    const Scene coarse = grey_room(dir, size, 256);
    EXPECT_NO_THROW(check_cost(coarse, CostCommand::Solve, limit)) << message;
  }
}
