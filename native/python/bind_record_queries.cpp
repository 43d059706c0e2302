// fenestra._core: the solver's queries of the path records (solve/record_queries.h) across the
// Python boundary. A shard's worker answers them for its sensors with LocalRecordQueries
// (`ShardQueries`); the client's solver asks them of a Python object that maps them over the shards
// (`solve_with_records`, fenestra.distributed). Rectangles travel as (n, 5) float64 arrays
// [panel, u0, u1, v0, v1] (meters in the panel's parameter domain): exact, unlike text. Climate
// goals' model stays in the shards, which answer in tallies (bind_climate_shards.cpp); annual
// coefficients travel as tuples of arrays (`annual_parts_tuple`), stacked by the client's side.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "annual/annual_cut_study.h"
#include "annual/annual_records.h"
#include "annual/annual_study.h"
#include "annual/hourly_flip_model.h"
#include "io/results.h"
#include "io/solve_result.h"
#include "scene/scene.h"
#include "solve/record_queries.h"
#include "solve/region_search.h"
#include "shard_queries.h"
#include "solve/solver.h"
#include "trace/contributions.h"
#include "util/progress.h"

namespace py = pybind11;
using namespace fenestra;

// bind_climate_shards.cpp: the climate model's shards across the boundary.
void bind_shard_climate(py::class_<ShardQueries, std::shared_ptr<ShardQueries>>& queries);
std::unique_ptr<ClimateModel> python_climate_model(const py::object& backend, const ClimateProblem& problem,
                                                   const std::vector<uint8_t>& about, const std::vector<uint8_t>& excluded);
ClimateTally python_climate_tally(const py::object& backend, const ClimateProblem& problem,
                                  const std::vector<uint8_t>& open);

// Annual coefficients and the occupied hours' mean of some sensors as (sources (sensors, sources)
// float64, direct (sensors, sun hours) float32, mean, stderr): what a shard sends of an annual study.
py::tuple annual_parts_tuple(const AnnualCoefficients& k, const SensorValues& mean) {
  py::array_t<float> direct({static_cast<py::ssize_t>(k.direct.rows()), static_cast<py::ssize_t>(k.direct.cols())});
  Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(direct.mutable_data(), k.direct.rows(),
                                                                                    k.direct.cols()) = k.direct;
  return py::make_tuple(py::cast(k.sources), direct, py::array_t<double>(mean.value.size(), mean.value.data()),
                        py::array_t<double>(mean.standard_error.size(), mean.standard_error.data()));
}

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using MaskArray = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;

py::array_t<double> rectangles_array(const std::vector<PanelRectangle>& rects) {
  py::array_t<double> a({static_cast<py::ssize_t>(rects.size()), py::ssize_t(5)});
  auto w = a.mutable_unchecked<2>();
  for (size_t i = 0; i < rects.size(); ++i) {
    const PanelRectangle& r = rects[i];
    const double row[5] = {static_cast<double>(r.panel), r.u0, r.u1, r.v0, r.v1};
    for (int k = 0; k < 5; ++k) w(static_cast<py::ssize_t>(i), k) = row[k];
  }
  return a;
}

std::vector<PanelRectangle> rectangles_of(const DoubleArray& a, const OpeningDomain& domain) {
  if (a.size() == 0) return {};
  if (a.ndim() != 2 || a.shape(1) != 5)
    throw std::invalid_argument("rectangles must have shape (n, 5): panel, u0, u1, v0, v1");
  std::vector<PanelRectangle> out(static_cast<size_t>(a.shape(0)));
  auto r = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    const double panel = r(i, 0);
    if (!(panel >= 0.0 && panel < static_cast<double>(domain.panels().size())) || panel != std::floor(panel))
      throw std::invalid_argument("rectangle " + std::to_string(i) + ": panel " + std::to_string(panel) +
                                  " is not a panel of the opening domain");
    static const char* const kNames[] = {"", "u0", "u1", "v0", "v1"};
    for (int k = 1; k < 5; ++k)
      if (!std::isfinite(r(i, k)))
        throw std::invalid_argument("rectangle " + std::to_string(i) + ": " + kNames[k] + " is not a finite number " +
                                    "of meters");
    out[i] = {static_cast<int>(panel), r(i, 1), r(i, 2), r(i, 3), r(i, 4)};
  }
  return out;
}

std::vector<uint8_t> mask_of(const MaskArray& a, size_t elements) {
  if (a.ndim() != 1 || static_cast<size_t>(a.shape(0)) != elements)
    throw std::invalid_argument("the open mask must have shape (" + std::to_string(elements) + ",)");
  return std::vector<uint8_t>(a.data(), a.data() + a.shape(0));
}

py::tuple values_pair(const SensorValues& v) {
  return py::make_tuple(py::array_t<double>(v.value.size(), v.value.data()),
                        py::array_t<double>(v.standard_error.size(), v.standard_error.data()));
}

Eigen::VectorXd vector_from(const py::handle& h, Eigen::Index size, const char* what) {
  const DoubleArray a = py::cast<DoubleArray>(h);
  if (a.ndim() != 1 || a.shape(0) != size)
    throw std::runtime_error(std::string(what) + ": expected " + std::to_string(size) + " values");
  return Eigen::Map<const Eigen::VectorXd>(a.data(), size);
}

SensorValues values_from(const py::object& pair, Eigen::Index sensors, const char* what) {
  const py::tuple t = py::cast<py::tuple>(pair);
  if (t.size() != 2) throw std::runtime_error(std::string(what) + ": expected (values, standard errors)");
  return {vector_from(t[0], sensors, what), vector_from(t[1], sensors, what)};
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;

template <typename T, typename Array>
std::vector<T> vector_of_array(const Array& a, const char* what) {
  if (a.ndim() != 1) throw std::runtime_error(std::string(what) + ": expected a one-dimensional array");
  return std::vector<T>(a.data(), a.data() + a.shape(0));
}

// An opening as openings files give it, in the scene's input coordinates (parse_openings reads it
// back into the local frame; numbers round-trip exactly, the frame's origin being whole meters).
nlohmann::json opening_json(const OpeningInput& o, const SiteFrame& site) {
  if (o.parameter) {
    const PanelRectangle& r = *o.parameter;
    return {{"panel", r.panel}, {"parameter_rectangle", {{"u0", r.u0}, {"u1", r.u1}, {"v0", r.v0}, {"v1", r.v1}}}};
  }
  nlohmann::json corners = nlohmann::json::array();
  for (const Vec3& c : o.corners) {
    const Vec3d p = site.to_site(c);
    corners.push_back(nlohmann::json::array({p.x(), p.y(), p.z()}));
  }
  return {{"corners", corners}};
}

AnnualRegionParts annual_parts_from(const py::handle& h, Eigen::Index sensors, const AnnualRecords& annual) {
  const py::tuple t = py::cast<py::tuple>(h);
  if (t.size() < 4) throw std::runtime_error("annual parts: expected (sources, direct, mean, stderr)");
  AnnualRegionParts parts;
  const DoubleArray sources = py::cast<DoubleArray>(t[0]);
  const FloatArray direct = py::cast<FloatArray>(t[1]);
  const py::ssize_t n_sources = annual.sources.count(), n_sun = static_cast<py::ssize_t>(annual.sun_hours.size());
  if (sources.ndim() != 2 || sources.shape(0) != sensors || sources.shape(1) != n_sources || direct.ndim() != 2 ||
      direct.shape(0) != sensors || direct.shape(1) != n_sun)
    throw std::runtime_error("annual parts: expected coefficients of " + std::to_string(sensors) + " sensors x " +
                             std::to_string(n_sources) + " sources and " + std::to_string(n_sun) + " sun hours");
  parts.coefficients.sources =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(sources.data(), sensors, n_sources);
  parts.coefficients.direct =
      Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(direct.data(), sensors, n_sun);
  parts.occupied_mean = {vector_from(t[2], sensors, "annual mean"), vector_from(t[3], sensors, "annual mean stderr")};
  return parts;
}

// A Python ValueError (bad input, e.g. a region the records cannot give) as the solver expects it.
template <typename F>
auto value_errors_as_invalid_argument(F f) {
  try {
    return f();
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError)) throw;
    throw std::invalid_argument(e.what());
  }
}

// The JSON text of an openings file with these openings.
std::string openings_text(const std::vector<OpeningInput>& openings, const SiteFrame& site) {
  nlohmann::json list = nlohmann::json::array();
  for (const OpeningInput& o : openings) list.push_back(opening_json(o, site));
  return nlohmann::json{{"openings", list}}.dump();
}

// ---- a shard's side: its records' answers -------------------------------------------------------

// LocalRecordQueries over one shard's contributions, kept alive with its scene.

struct ShardRegionSearch {
  std::shared_ptr<ShardQueries> owner;  // the records it indexes
  std::unique_ptr<RegionQueries> search;
};

void bind_shard_queries(py::module_& m) {
  py::class_<ShardRegionSearch>(m, "RegionSearch",
                                "An open region searched a little at a time (exact values from the records).")
      .def_property_readonly("values", [](const ShardRegionSearch& s) { return Eigen::VectorXd(s.search->values()); })
      .def(
          "try_region",
          [](ShardRegionSearch& s, const DoubleArray& rects) {
            const std::vector<PanelRectangle> candidate = rectangles_of(rects, s.owner->scene->domain);
            py::gil_scoped_release release;
            return Eigen::VectorXd(s.search->try_region(candidate));
          },
          py::arg("rectangles"), "Values per sensor with these rectangles (n, 5) instead; remembered for accept().")
      .def("accept", [](ShardRegionSearch& s) { s.search->accept(); }, "Makes the last try the current region.");

  py::class_<ShardQueries, std::shared_ptr<ShardQueries>> queries(
      m, "RecordQueries",
      "What the solver asks of path records (exact values of element sets and regions, flip effects, region "
      "searches, climate goals' model shards), answered from these contributions' records: a shard's sensors when "
      "they are a shard's.");
  queries
      .def(py::init([](std::shared_ptr<const Scene> scene, std::shared_ptr<const Contributions> c,
                       const py::object& sensors) {
             if (c->element_count() != scene->domain.element_count())
               throw std::invalid_argument("the contributions have " + std::to_string(c->element_count()) +
                                           " elements, the scene " + std::to_string(scene->domain.element_count()));
             SensorRange range;
             if (!sensors.is_none()) {
               const auto pair = sensors.cast<std::pair<size_t, size_t>>();
               range = {pair.first, pair.second};
               if (range.end > scene->sensors.size() || range.size() != c->sensor_count())
                 throw std::invalid_argument("sensors (" + std::to_string(range.begin) + ", " + std::to_string(range.end) +
                                             ") are not the contributions' " + std::to_string(c->sensor_count()) +
                                             " sensors of the scene's " + std::to_string(scene->sensors.size()));
             }
             return std::make_shared<ShardQueries>(std::move(scene), std::move(c), range);
           }),
           py::arg("scene"), py::arg("contributions"), py::arg("sensors") = py::none())
      .def(
          "exact",
          [](ShardQueries& q, const MaskArray& open) {
            const std::vector<uint8_t> mask = mask_of(open, q.contributions->element_count());
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = q.queries.exact(mask);
            }
            return values_pair(v);
          },
          py::arg("open"), "Exact (values, standard errors) with these elements open (kept; near sets from a reference).")
      .def(
          "sampled",
          [](ShardQueries& q, const MaskArray& open) {
            const std::vector<uint8_t> mask = mask_of(open, q.contributions->element_count());
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = q.queries.sampled(mask);
            }
            return values_pair(v);
          },
          py::arg("open"),
          "(values, sampling errors) with these elements open from one in four of the paths the change met since "
          "each sensor's nearest set (a screen before exact; the references are left as they are).")
      .def(
          "evaluate",
          [](ShardQueries& q, const DoubleArray& rects) {
            const std::vector<PanelRectangle> region = rectangles_of(rects, q.scene->domain);
            SensorValues v;
            {
              py::gil_scoped_release release;
              v = q.queries.evaluate(region);
            }
            return values_pair(v);
          },
          py::arg("rectangles"), "Exact (values, standard errors) with these rectangles (n, 5) open.")
      .def(
          "flip_effects",
          [](ShardQueries& q, const MaskArray& about) {
            const std::vector<uint8_t> mask = mask_of(about, q.contributions->element_count());
            py::gil_scoped_release release;
            return q.queries.flip_effects(mask);
          },
          py::arg("about"), "What flipping each element alone changes at each sensor: (sensors, elements).")
      .def(
          "region_search",
          [](std::shared_ptr<ShardQueries> q, const DoubleArray& rects) {
            const std::vector<PanelRectangle> start = rectangles_of(rects, q->scene->domain);
            ShardRegionSearch s{q, nullptr};
            {
              py::gil_scoped_release release;
              s.search = q->queries.region_search(start);
            }
            return s;
          },
          py::arg("rectangles"), "A region search starting from these rectangles (n, 5).")
      .def_property_readonly("record_bytes", [](const ShardQueries& q) { return q.queries.record_bytes(); })
      .def(
          "sensors_reached",
          [](ShardQueries& q, const DoubleArray& before, const DoubleArray& after) {
            const std::vector<PanelRectangle> b = rectangles_of(before, q.scene->domain),
                                              a = rectangles_of(after, q.scene->domain);
            py::gil_scoped_release release;
            return q.queries.sensors_reached(b, a);
          },
          py::arg("before"), py::arg("after"),
          "These records' sensors (positions, ascending) that a change of openings from the rectangles `before` to "
          "`after` (n, 5) can reach: those whose paths met an element near it.")
      .def(
          "annual_parts",
          [](ShardQueries& q, const DoubleArray& rects) {
            const OpenRegion region(q.scene->domain, rectangles_of(rects, q.scene->domain));
            AnnualRegionParts parts;
            {
              py::gil_scoped_release release;
              parts = annual_region_parts(*q.contributions, region);
            }
            return annual_parts_tuple(parts.coefficients, parts.occupied_mean);
          },
          py::arg("rectangles"),
          "The annual coefficients and occupied hours' mean of these rectangles (n, 5) open: (sources, direct, "
          "mean, stderr).");
  bind_shard_climate(queries);
}

// ---- the client's side: a Python object answers for all shards ----------------------------------

// Every call takes the GIL: the solver runs with it released.
class PythonRegionQueries : public RegionQueries {
 public:
  PythonRegionQueries(py::object search, std::vector<PanelRectangle> start, Eigen::Index sensors)
      : search_(std::move(search)), rectangles_(std::move(start)), sensors_(sensors) {
    py::gil_scoped_acquire gil;
    values_ = vector_from(search_.attr("values"), sensors_, "region search values");
  }
  ~PythonRegionQueries() override {
    py::gil_scoped_acquire gil;
    try {
      search_.attr("close")();
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("closing a region search");
    }
    search_ = py::object();
  }
  const Eigen::VectorXd& values() const override { return values_; }
  const std::vector<PanelRectangle>& rectangles() const override { return rectangles_; }
  const Eigen::VectorXd& try_region(const std::vector<PanelRectangle>& candidate) override {
    py::gil_scoped_acquire gil;
    candidate_values_ = vector_from(search_.attr("try_region")(rectangles_array(candidate)), sensors_, "region try");
    candidate_ = candidate;
    return candidate_values_;
  }
  void accept() override {
    py::gil_scoped_acquire gil;
    search_.attr("accept")();
    rectangles_ = candidate_;
    values_ = candidate_values_;
  }

 private:
  py::object search_;
  std::vector<PanelRectangle> rectangles_, candidate_;
  Eigen::VectorXd values_, candidate_values_;
  Eigen::Index sensors_;
};

class PythonRecordQueries : public RecordQueries {
 public:
  PythonRecordQueries(const Scene& scene, const Contributions& c, py::object backend)
      : scene_(scene), c_(c), backend_(std::move(backend)), annual_(scene.climate ? prepare_annual(scene) : nullptr) {}
  ~PythonRecordQueries() override {
    py::gil_scoped_acquire gil;
    backend_ = py::object();
  }
  const Contributions& contributions() const override { return c_; }
  const SensorValues& exact(const std::vector<uint8_t>& open) override {
    auto it = known_.find(open);  // as ExactValues keeps them: a known set is not asked again
    if (it != known_.end()) return it->second;
    py::gil_scoped_acquire gil;
    py::array_t<uint8_t> mask(static_cast<py::ssize_t>(open.size()), open.data());
    return known_.emplace(open, values_from(backend_.attr("exact")(mask), sensors(), "exact values")).first->second;
  }
  SensorValues sampled(const std::vector<uint8_t>& open) override {
    {
      py::gil_scoped_acquire gil;
      if (py::hasattr(backend_, "sampled")) {
        py::array_t<uint8_t> mask(static_cast<py::ssize_t>(open.size()), open.data());
        return values_from(backend_.attr("sampled")(mask), sensors(), "sampled values");
      }
    }
    return RecordQueries::sampled(open);  // a backend without a screen: the exact values
  }
  SensorValues evaluate(const std::vector<PanelRectangle>& region) override {
    py::gil_scoped_acquire gil;
    return values_from(backend_.attr("evaluate")(rectangles_array(region)), sensors(), "region values");
  }
  Eigen::MatrixXd flip_effects(const std::vector<uint8_t>& about) override {
    return flip_effects_.about(about, [&] {
      py::gil_scoped_acquire gil;
      py::array_t<uint8_t> mask(static_cast<py::ssize_t>(about.size()), about.data());
      Eigen::MatrixXd D = py::cast<Eigen::MatrixXd>(backend_.attr("flip_effects")(mask));
      if (D.rows() != sensors() || D.cols() != static_cast<Eigen::Index>(c_.element_count()))
        throw std::runtime_error("flip effects: expected " + std::to_string(sensors()) + " x " +
                                 std::to_string(c_.element_count()));
      return D;
    });
  }
  std::unique_ptr<RegionQueries> region_search(const std::vector<PanelRectangle>& start) override {
    py::gil_scoped_acquire gil;
    py::object search = backend_.attr("region_search")(rectangles_array(start));
    return std::make_unique<PythonRegionQueries>(std::move(search), start, sensors());
  }
  SensorValues cut(const std::vector<OpeningInput>& openings, int paths, uint64_t stream) override {
    const std::string text = openings_text(openings, scene_.site);
    py::gil_scoped_acquire gil;
    return values_from(backend_.attr("cut")(text, paths, stream), sensors(), "values with real cutters");
  }
  // A cut keeps its values at the sensors a change cannot reach, so the backend must name the same
  // sensors as one process's records would (else every sensor, as the default).
  std::vector<size_t> sensors_reached(const std::vector<PanelRectangle>& before,
                                      const std::vector<PanelRectangle>& after) override {
    std::vector<int64_t> reached;
    {
      py::gil_scoped_acquire gil;
      if (!py::hasattr(backend_, "sensors_reached")) return RecordQueries::sensors_reached(before, after);
      using Int64Array = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
      reached = vector_of_array<int64_t>(
          py::cast<Int64Array>(backend_.attr("sensors_reached")(rectangles_array(before), rectangles_array(after))),
          "sensors reached");
    }
    std::vector<size_t> out;
    for (const int64_t s : reached) {
      if (s < 0 || s >= sensors() || (!out.empty() && static_cast<size_t>(s) <= out.back()))
        throw std::runtime_error("sensors reached: expected ascending sensors of " + std::to_string(sensors()));
      out.push_back(static_cast<size_t>(s));
    }
    return out;
  }
  double record_bytes() const override {
    py::gil_scoped_acquire gil;
    return py::cast<double>(backend_.attr("record_bytes")());
  }
  std::shared_ptr<const AnnualRecords> annual() const override { return annual_; }
  std::unique_ptr<ClimateModel> climate_model(const ClimateProblem& problem, const std::vector<uint8_t>& about,
                                              const std::vector<uint8_t>& excluded) override {
    require_annual();
    return python_climate_model(backend_, problem, about, excluded);
  }
  ClimateTally climate_tally(const ClimateProblem& problem, const std::vector<uint8_t>& open) override {
    require_annual();
    return python_climate_tally(backend_, problem, open);
  }
  AnnualStudy annual_study(const std::vector<PanelRectangle>& region) override {
    require_annual();
    const auto start = std::chrono::steady_clock::now();
    AnnualRegionParts parts;
    {
      py::gil_scoped_acquire gil;
      parts = value_errors_as_invalid_argument(
          [&] { return annual_parts_from(backend_.attr("annual_parts")(rectangles_array(region)), sensors(), *annual_); });
    }
    AnnualStudy study = annual_study_of(parts.coefficients, annual_, parts.occupied_mean);
    study.paths_per_sensor = c_.paths_per_sensor;
    study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return study;
  }
  AnnualStudy annual_cut(const std::vector<OpeningInput>& openings, int paths) override {
    require_annual();
    const auto start = std::chrono::steady_clock::now();
    AnnualCutCoefficients whole;
    {
      py::gil_scoped_acquire gil;
      const py::tuple answer = backend_.attr("annual_cut")(openings_text(openings, scene_.site), paths);
      AnnualRegionParts parts = annual_parts_from(answer, sensors(), *annual_);
      whole.coefficients = std::move(parts.coefficients);
      whole.occupied_mean = std::move(parts.occupied_mean);
      whole.paths_per_sensor = py::cast<int>(answer[4]);
      whole.annual = annual_;
    }
    AnnualStudy study = annual_cut_study_of(scene_, std::move(whole));
    study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return study;
  }

 private:
  Eigen::Index sensors() const { return c_.closed.value.size(); }
  void require_annual() const {
    if (!annual_) throw std::invalid_argument("scene '" + scene_.source + "': climate goals need a climate sky");
  }

  const Scene& scene_;
  const Contributions& c_;
  py::object backend_;
  std::shared_ptr<const AnnualRecords> annual_;
  std::map<std::vector<uint8_t>, SensorValues> known_;
  FlipEffectsCache flip_effects_;  // as LocalRecordQueries keeps them
};

void bind_solve_with_records(py::module_& m) {
  m.def(
      "solve_with_records",
      [](const Scene& scene, const Contributions& c, py::object backend, std::shared_ptr<Progress> progress) {
        PythonRecordQueries records(scene, c, std::move(backend));
        std::string text;
        {
          py::gil_scoped_release release;
          const SolveResult r = solve_openings(scene, records, progress.get());
          text = solve_result_json(scene, r).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        }
        return text;
      },
      py::arg("scene"), py::arg("contributions"), py::arg("records"), py::arg("progress") = nullptr,
      "The opening solver on contributions whose path records `records` holds: an object with exact(open), "
      "evaluate(rectangles), flip_effects(about), region_search(rectangles) (values, try_region, accept, close), "
      "cut(openings_json, paths), record_bytes(), and for climate goals climate_model(about, excluded, goals) (an "
      "object with settle(slots, bases, packed states), flip_tallies(slot, elements), model_bytes and close()), "
      "climate_tally(open, goals), "
      "annual_parts(rectangles) and annual_cut(openings_json, paths) (fenestra.distributed). Returns the result as JSON text.");
}

}  // namespace

AnnualRegionParts annual_parts_of(const py::handle& parts, Eigen::Index sensors, const AnnualRecords& annual) {
  return annual_parts_from(parts, sensors, annual);
}

void bind_record_queries(py::module_& m) {
  bind_shard_queries(m);
  bind_solve_with_records(m);
}
