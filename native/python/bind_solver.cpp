// Python bindings of the solver's building blocks (NNLS, the genetic algorithm).
#include <pybind11/pybind11.h>

namespace py = pybind11;

void bind_solver(py::module_& m) { (void)m; }
