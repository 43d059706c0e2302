// fenestra._core: the solver's queries of the path records (solve/record_queries.h) across the
// Python boundary. A shard's worker answers them for its sensors with LocalRecordQueries
// (`ShardQueries`); the client's solver asks them of a Python object that maps them over the shards
// (`solve_with_records`, fenestra.distributed). Rectangles travel as (n, 5) float64 arrays
// [panel, u0, u1, v0, v1] (meters in the panel's parameter domain): exact, unlike text.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/results.h"
#include "io/solve_result.h"
#include "scene/scene.h"
#include "solve/record_queries.h"
#include "solve/region_search.h"
#include "solve/solver.h"
#include "trace/contributions.h"
#include "util/progress.h"

namespace py = pybind11;
using namespace fenestra;

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

// An opening as openings files give it (parse_openings reads it back; numbers round-trip exactly).
nlohmann::json opening_json(const OpeningInput& o) {
  if (o.parameter) {
    const PanelRectangle& r = *o.parameter;
    return {{"panel", r.panel}, {"parameter_rectangle", {{"u0", r.u0}, {"u1", r.u1}, {"v0", r.v0}, {"v1", r.v1}}}};
  }
  nlohmann::json corners = nlohmann::json::array();
  for (const Vec3& c : o.corners) corners.push_back(nlohmann::json::array({c.x(), c.y(), c.z()}));
  return {{"corners", corners}};
}

// ---- a shard's side: its records' answers -------------------------------------------------------

// LocalRecordQueries over one shard's contributions, kept alive with its scene.
struct ShardQueries {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const Contributions> contributions;
  LocalRecordQueries queries;
  ShardQueries(std::shared_ptr<const Scene> s, std::shared_ptr<const Contributions> c)
      : scene(std::move(s)), contributions(std::move(c)), queries(*scene, *contributions, scene->domain, nullptr) {}
};

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

  py::class_<ShardQueries, std::shared_ptr<ShardQueries>>(
      m, "RecordQueries",
      "What the solver asks of path records (exact values of element sets and regions, flip effects, region "
      "searches), answered from these contributions' records: a shard's sensors when they are a shard's.")
      .def(py::init([](std::shared_ptr<const Scene> scene, std::shared_ptr<const Contributions> c) {
             if (c->element_count() != scene->domain.element_count())
               throw std::invalid_argument("the contributions have " + std::to_string(c->element_count()) +
                                           " elements, the scene " + std::to_string(scene->domain.element_count()));
             return std::make_shared<ShardQueries>(std::move(scene), std::move(c));
           }),
           py::arg("scene"), py::arg("contributions"))
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
      .def_property_readonly("record_bytes", [](const ShardQueries& q) { return q.queries.record_bytes(); });
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
  PythonRecordQueries(const Contributions& c, py::object backend) : c_(c), backend_(std::move(backend)) {}
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
  SensorValues evaluate(const std::vector<PanelRectangle>& region) override {
    py::gil_scoped_acquire gil;
    return values_from(backend_.attr("evaluate")(rectangles_array(region)), sensors(), "region values");
  }
  Eigen::MatrixXd flip_effects(const std::vector<uint8_t>& about) override {
    py::gil_scoped_acquire gil;
    py::array_t<uint8_t> mask(static_cast<py::ssize_t>(about.size()), about.data());
    Eigen::MatrixXd D = py::cast<Eigen::MatrixXd>(backend_.attr("flip_effects")(mask));
    if (D.rows() != sensors() || D.cols() != static_cast<Eigen::Index>(c_.element_count()))
      throw std::runtime_error("flip effects: expected " + std::to_string(sensors()) + " x " +
                               std::to_string(c_.element_count()));
    return D;
  }
  std::unique_ptr<RegionQueries> region_search(const std::vector<PanelRectangle>& start) override {
    py::gil_scoped_acquire gil;
    py::object search = backend_.attr("region_search")(rectangles_array(start));
    return std::make_unique<PythonRegionQueries>(std::move(search), start, sensors());
  }
  SensorValues cut(const std::vector<OpeningInput>& openings, int paths) override {
    nlohmann::json list = nlohmann::json::array();
    for (const OpeningInput& o : openings) list.push_back(opening_json(o));
    const std::string text = nlohmann::json{{"openings", list}}.dump();
    py::gil_scoped_acquire gil;
    return values_from(backend_.attr("cut")(text, paths), sensors(), "values with real cutters");
  }
  double record_bytes() const override {
    py::gil_scoped_acquire gil;
    return py::cast<double>(backend_.attr("record_bytes")());
  }

 private:
  Eigen::Index sensors() const { return c_.closed.value.size(); }

  const Contributions& c_;
  py::object backend_;
  std::map<std::vector<uint8_t>, SensorValues> known_;
};

void bind_solve_with_records(py::module_& m) {
  m.def(
      "solve_with_records",
      [](const Scene& scene, const Contributions& c, py::object backend, std::shared_ptr<Progress> progress) {
        PythonRecordQueries records(c, std::move(backend));
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
      "cut(openings_json, paths) and record_bytes() (fenestra.distributed). Returns the result as JSON text.");
}

}  // namespace

void bind_record_queries(py::module_& m) {
  bind_shard_queries(m);
  bind_solve_with_records(m);
}
