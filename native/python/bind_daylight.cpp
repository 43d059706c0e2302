// Python bindings of the daylight models (solar position, analytic skies).
#include <pybind11/pybind11.h>

namespace py = pybind11;

void bind_daylight(py::module_& m) { (void)m; }
