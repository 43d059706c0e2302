// Python bindings of the solver's building blocks (NNLS, the genetic algorithm).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

#include <pybind11/stl.h>

#include "scene/opening_constraints.h"
#include "solve/nnls.h"

namespace py = pybind11;

namespace {

// ---- Non-negative least squares ----

void bind_nnls(py::module_& m) {
  using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
  m.def(
      "nnls",
      [](InArray A, InArray b, int max_iterations, double tolerance) {
        if (A.ndim() != 2)
          throw std::invalid_argument("nnls: A must have shape (m, n), got " + std::to_string(A.ndim()) + " dimensions");
        if (b.ndim() != 1)
          throw std::invalid_argument("nnls: b must have shape (m,), got " + std::to_string(b.ndim()) + " dimensions");
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        fenestra::NnlsResult result;
        {
          // The arguments keep both buffers alive while the GIL is released.
          py::gil_scoped_release release;
          const Eigen::MatrixXd a = Eigen::Map<const RowMajor>(A.data(), A.shape(0), A.shape(1));
          const Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd>(b.data(), b.shape(0));
          result = fenestra::nnls(a, rhs, max_iterations, tolerance);
        }
        if (!result.converged)
          throw std::runtime_error("nnls: not converged after " + std::to_string(result.iterations) +
                                   " iterations; raise max_iterations or tolerance");
        auto* x = new Eigen::VectorXd(std::move(result.x));
        py::capsule owner(x, [](void* p) { delete static_cast<Eigen::VectorXd*>(p); });
        return py::make_tuple(py::array_t<double>(x->size(), x->data(), owner), result.residual_norm);
      },
      py::arg("A"), py::arg("b"), py::arg("max_iterations") = 0, py::arg("tolerance") = 0.0,
      "Solves min ||A x - b|| subject to x >= 0 (Lawson-Hanson); returns (x, residual_norm), float64.\n"
      "max_iterations 0: 3 n. tolerance 0: 10 eps max(m, n) ||A||_1 ||b||, the bound on the gradient\n"
      "A^T (b - A x) where x = 0. Raises ValueError on bad shapes or non-finite input, RuntimeError if\n"
      "the iteration limit is reached.");
}

// ---- What openings are when the user says nothing ----

void bind_automatic_constraints(py::module_& m) {
  m.def(
      "automatic_constraints",
      [](bool full_height, bool climate) {
        py::dict out;
        for (const fenestra::AutomaticConstraint& a : fenestra::automatic_constraints(full_height, climate))
          out[a.key] = py::make_tuple(a.value, a.why);
        return out;
      },
      py::arg("full_height") = false, py::arg("climate") = false,
      "The solver.constraints keys that take an automatic value when not given (and \"automatic\" is\n"
      "on): {key: (value, explanation)}, lengths in meters, areas in m^2. full_height: doors and\n"
      "floor-to-ceiling glazing allowed (no automatic sill, head or margin); climate: a study with\n"
      "climate goals (openings of at least 1 m^2).");
}

void bind_catalogues(py::module_& m) {
  m.def(
      "catalogues",
      [] {
        auto sizes = [](const std::vector<fenestra::CatalogueSize>& list) {
          py::list out;
          for (const fenestra::CatalogueSize& s : list) out.append(py::make_tuple(s.width, s.height));
          return out;
        };
        py::dict out;
        for (const std::string& name : fenestra::catalogue_names()) {
          const fenestra::WindowCatalogue c = fenestra::builtin_catalogue(name);
          py::dict entry;
          entry["walls"] = sizes(c.walls);
          entry["roofs"] = sizes(c.roofs);
          out[name.c_str()] = entry;
        }
        return out;
      },
      "The built-in window catalogues (solver.constraints.catalogue by name): {name: {\"walls\": [(width, "
      "height), ...], \"roofs\": [...]}}, meters; walls' widths are horizontal.");
}

}  // namespace

void bind_solver(py::module_& m) {
  bind_nnls(m);
  bind_automatic_constraints(m);
  bind_catalogues(m);
}
