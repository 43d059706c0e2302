// fenestra._core: the climate goals' hourly model in shards across the Python boundary
// (solve/climate_model.h). A worker's RecordQueries builds its shard of the model from its records
// and settles the search's states in it; the client's solver asks a Python object that maps each
// call over the shards (fenestra.distributed) and adds the tallies that come back. States travel
// packed eight elements to a byte, tallies as tuples of arrays, the per-sensor goals as one array
// (target, weight, lower, upper per sensor).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shard_queries.h"
#include "solve/climate_model.h"

namespace py = pybind11;
using namespace fenestra;

namespace {

using MaskArray = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <typename T>
py::array_t<T> array_of(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::list count_lists(const std::vector<std::vector<int32_t>>& counts) {
  py::list out;
  for (const auto& c : counts) out.append(array_of(c));
  return out;
}

py::tuple tally_tuple(const ClimateTally& t) {
  return py::make_tuple(count_lists(t.hours), array_of(t.occupied_sum), count_lists(t.above_target),
                        count_lists(t.above_minimum));
}

py::list tally_list(const std::vector<ClimateTally>& tallies) {
  py::list out;
  for (const ClimateTally& t : tallies) out.append(tally_tuple(t));
  return out;
}

std::vector<std::vector<int32_t>> counts_from(const py::handle& h) {
  std::vector<std::vector<int32_t>> out;
  for (const py::handle item : py::cast<py::list>(h)) {
    const IntArray a = py::cast<IntArray>(item);
    if (a.ndim() != 1) throw std::runtime_error("climate tally: counts must be 1-dimensional");
    out.emplace_back(a.data(), a.data() + a.size());
  }
  return out;
}

ClimateTally tally_from(const py::handle& h) {
  const py::tuple t = py::cast<py::tuple>(h);
  if (t.size() != 4) throw std::runtime_error("climate tally: expected (hours, occupied sums, above target, above minimum)");
  ClimateTally out;
  out.hours = counts_from(t[0]);
  const DoubleArray sums = py::cast<DoubleArray>(t[1]);
  out.occupied_sum.assign(sums.data(), sums.data() + sums.size());
  out.above_target = counts_from(t[2]);
  out.above_minimum = counts_from(t[3]);
  return out;
}

// Per shard, its tallies: the list the backend answers.
std::vector<std::vector<ClimateTally>> shard_tallies(const py::handle& answer) {
  std::vector<std::vector<ClimateTally>> out;
  for (const py::handle shard : py::cast<py::list>(answer)) {
    std::vector<ClimateTally> tallies;
    for (const py::handle t : py::cast<py::list>(shard)) tallies.push_back(tally_from(t));
    out.push_back(std::move(tallies));
  }
  if (out.empty()) throw std::runtime_error("climate model: no shard answered");
  return out;
}

// States packed eight elements to a byte, the first element in the lowest bit.
py::array_t<uint8_t> packed_states(const std::vector<ClimateRecipe>& batch, size_t elements) {
  const size_t width = (elements + 7) / 8;
  py::array_t<uint8_t> out({static_cast<py::ssize_t>(batch.size()), static_cast<py::ssize_t>(width)});
  uint8_t* data = out.mutable_data();
  std::memset(data, 0, batch.size() * width);
  for (size_t i = 0; i < batch.size(); ++i)
    for (size_t k = 0; k < elements; ++k)
      if (batch[i].open[k]) data[i * width + k / 8] |= static_cast<uint8_t>(1u << (k % 8));
  return out;
}

std::vector<uint8_t> unpacked(const uint8_t* row, size_t elements) {
  std::vector<uint8_t> open(elements);
  for (size_t k = 0; k < elements; ++k) open[k] = (row[k / 8] >> (k % 8)) & 1u;
  return open;
}

py::array_t<double> goals_array(const SolverGoals& g) {
  const Eigen::Index n = g.weight.size();
  py::array_t<double> out(4 * n);
  double* d = out.mutable_data();
  for (Eigen::Index i = 0; i < n; ++i) d[i] = g.target[i], d[n + i] = g.weight[i], d[2 * n + i] = g.lower[i], d[3 * n + i] = g.upper[i];
  return out;
}

SolverGoals goals_from(const DoubleArray& a, Eigen::Index sensors) {
  if (a.ndim() != 1 || a.size() != 4 * sensors)
    throw std::invalid_argument("climate goals: expected the target, weight, lower and upper of " +
                                std::to_string(sensors) + " sensors");
  const Eigen::Map<const Eigen::VectorXd> v(a.data(), a.size());
  SolverGoals g;
  g.target = v.segment(0, sensors), g.weight = v.segment(sensors, sensors);
  g.lower = v.segment(2 * sensors, sensors), g.upper = v.segment(3 * sensors, sensors);
  g.given = Eigen::VectorXd::Constant(sensors, NAN);
  return g;
}

bool same_bits(const Eigen::VectorXd& a, const DoubleArray& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

std::vector<uint8_t> mask_of(const MaskArray& a, size_t elements, const char* what) {
  if (a.ndim() != 1 || static_cast<size_t>(a.size()) != elements)
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(elements) + " elements");
  std::vector<uint8_t> out(a.data(), a.data() + a.size());
  for (uint8_t& v : out)
    if (v > 1) throw std::invalid_argument(std::string(what) + ": values must be 0 or 1");
  return out;
}

// The shard's problem for these goals (built, or rebuilt with its model dropped, when they change).
const ClimateProblem& shard_problem(ShardQueries& q, const DoubleArray& goals) {
  if (q.climate_problem && same_bits(q.climate_goals, goals)) return *q.climate_problem;
  if (!q.contributions->annual) throw std::invalid_argument("climate goals: these contributions are not a climate sky's");
  const SolverGoals linear = goals_from(goals, static_cast<Eigen::Index>(q.scene->sensors.size()));
  q.climate_shard.reset();  // built on the problem it replaces
  q.climate_problem = std::make_unique<ClimateProblem>(climate_problem(*q.scene, q.contributions->annual.get(), linear));
  q.climate_goals = Eigen::Map<const Eigen::VectorXd>(goals.data(), goals.size());
  return *q.climate_problem;
}

ClimateShard& shard_of(ShardQueries& q) {
  if (!q.climate_shard) throw std::invalid_argument("climate model: none was built on these records");
  return *q.climate_shard;
}

// The client's side: a backend object (fenestra.distributed) maps each call over the shards.
class PythonClimateModel : public ClimateModel {
 public:
  PythonClimateModel(py::object model, const ClimateObjective& objective, size_t elements)
      : model_(std::move(model)), objective_(objective), elements_(elements) {}
  ~PythonClimateModel() override {
    py::gil_scoped_acquire gil;
    try {
      model_.attr("close")();
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("closing the climate model's shards");
    }
    model_ = py::object();
  }
  std::vector<ClimateTally> settle(const std::vector<ClimateRecipe>& batch) override {
    std::vector<int32_t> slots, bases;
    for (const ClimateRecipe& r : batch) slots.push_back(r.slot), bases.push_back(r.base);
    py::gil_scoped_acquire gil;
    return added_tallies(objective_,
                         shard_tallies(model_.attr("settle")(array_of(slots), array_of(bases), packed_states(batch, elements_))),
                         batch.size());
  }
  std::vector<ClimateTally> flip_tallies(int slot, const std::vector<int>& elements) override {
    py::gil_scoped_acquire gil;
    const std::vector<int32_t> e(elements.begin(), elements.end());
    return added_tallies(objective_, shard_tallies(model_.attr("flip_tallies")(slot, array_of(e))), elements.size());
  }
  double model_bytes() const override {
    py::gil_scoped_acquire gil;
    return py::cast<double>(model_.attr("model_bytes"));
  }

 private:
  py::object model_;
  const ClimateObjective& objective_;
  size_t elements_;
};

}  // namespace

std::unique_ptr<ClimateModel> python_climate_model(const py::object& backend, const ClimateProblem& problem,
                                                   const std::vector<uint8_t>& about, const std::vector<uint8_t>& excluded) {
  std::vector<uint8_t> dropped = excluded;
  dropped.resize(about.size(), 0);
  py::gil_scoped_acquire gil;
  py::object model = backend.attr("climate_model")(array_of(about), array_of(dropped), goals_array(problem.linear));
  return std::make_unique<PythonClimateModel>(std::move(model), *problem.objective, about.size());
}

ClimateTally python_climate_tally(const py::object& backend, const ClimateProblem& problem,
                                  const std::vector<uint8_t>& open) {
  py::gil_scoped_acquire gil;
  py::list answer;
  for (const py::handle t : py::cast<py::list>(backend.attr("climate_tally")(array_of(open), goals_array(problem.linear))))
  {
    py::list one;  // one state per shard
    one.append(t);
    answer.append(one);
  }
  return added_tallies(*problem.objective, shard_tallies(answer), 1)[0];
}

void bind_shard_climate(py::class_<ShardQueries, std::shared_ptr<ShardQueries>>& c) {
  c.def(
       "climate_model",
       [](ShardQueries& q, const MaskArray& about, const MaskArray& excluded, const DoubleArray& goals) {
         const size_t n = q.contributions->element_count();
         const std::vector<uint8_t> a = mask_of(about, n, "climate model state"), x = mask_of(excluded, n, "excluded elements");
         const ClimateProblem& problem = shard_problem(q, goals);
         q.climate_shard.reset();  // one model at a time
         py::gil_scoped_release release;
         q.climate_shard = q.queries.climate_shard(problem, a, x);
         return static_cast<double>(q.climate_shard->model_bytes());
       },
       py::arg("about"), py::arg("excluded"), py::arg("goals"),
       "Builds this shard of the climate goals' hourly model about `about` (the excluded elements' flips dropped) "
       "for the per-sensor goals `goals` (target, weight, lower, upper per sensor); returns its bytes.")
      .def(
          "climate_model_bytes",
          [](ShardQueries& q, const MaskArray& excluded, const DoubleArray& goals) {
            const std::vector<uint8_t> x = mask_of(excluded, q.contributions->element_count(), "excluded elements");
            const ClimateProblem& problem = shard_problem(q, goals);
            py::gil_scoped_release release;
            return q.queries.climate_shard_bytes(problem, x);
          },
          py::arg("excluded"), py::arg("goals"),
          "Bytes this shard's part of the climate goals' hourly model will hold for the per-sensor goals `goals`, "
          "the excluded elements' flips left out, counted from its records before it is built (about any state).")
      .def(
          "climate_settle",
          [](ShardQueries& q, const IntArray& slots, const IntArray& bases, const MaskArray& states) {
            ClimateShard& shard = shard_of(q);
            const size_t n = q.contributions->element_count(), width = (n + 7) / 8;
            if (slots.ndim() != 1 || bases.ndim() != 1 || slots.size() != bases.size() || states.ndim() != 2 ||
                states.shape(0) != slots.size() || static_cast<size_t>(states.shape(1)) != width)
              throw std::invalid_argument("climate settle: expected as many slots, bases and packed states of " +
                                          std::to_string(n) + " elements");
            std::vector<ClimateRecipe> batch(static_cast<size_t>(slots.size()));
            for (size_t i = 0; i < batch.size(); ++i)
              batch[i] = {slots.data()[i], bases.data()[i], unpacked(states.data() + i * width, n)};
            std::vector<ClimateTally> tallies;
            {
              py::gil_scoped_release release;
              tallies = shard.settle(batch);
            }
            return tally_list(tallies);
          },
          py::arg("slots"), py::arg("bases"), py::arg("states"),
          "Settles states (packed eight elements to a byte) in the model's slots, each derived from its base's "
          "(-1: the model's state); returns each state's tally of this shard's sensors.")
      .def(
          "climate_flip_tallies",
          [](ShardQueries& q, int slot, const IntArray& elements) {
            ClimateShard& shard = shard_of(q);
            const std::vector<int> e(elements.data(), elements.data() + elements.size());
            std::vector<ClimateTally> tallies;
            {
              py::gil_scoped_release release;
              tallies = shard.flip_tallies(slot, e);
            }
            return tally_list(tallies);
          },
          py::arg("slot"), py::arg("elements"), "The tallies of the state in `slot` with each element flipped alone.")
      .def(
          "climate_tally",
          [](ShardQueries& q, const MaskArray& open, const DoubleArray& goals) {
            const std::vector<uint8_t> o = mask_of(open, q.contributions->element_count(), "climate state");
            // Other goals than the model's get a problem of their own: the model stays as it is.
            std::unique_ptr<ClimateProblem> other;
            if (!(q.climate_problem && same_bits(q.climate_goals, goals))) {
              if (!q.contributions->annual)
                throw std::invalid_argument("climate goals: these contributions are not a climate sky's");
              other = std::make_unique<ClimateProblem>(climate_problem(
                  *q.scene, q.contributions->annual.get(), goals_from(goals, static_cast<Eigen::Index>(q.scene->sensors.size()))));
            }
            const ClimateProblem* problem = other ? other.get() : q.climate_problem.get();
            ClimateTally t;
            {
              py::gil_scoped_release release;
              t = q.queries.climate_tally(*problem, o);
            }
            return tally_tuple(t);
          },
          py::arg("open"), py::arg("goals"), "The tally of the exact year of `open` at this shard's goal sensors.")
      .def(
          "climate_close", [](ShardQueries& q) { q.climate_shard.reset(); },
          "Frees this shard of the climate model and its states.");
}
