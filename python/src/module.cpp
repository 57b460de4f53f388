// _spdfit: the compiled half of the spdfit Python package (python/spdfit/__init__.py is the
// public face; it turns warnings into Python warnings and failures into exceptions).
#include <pybind11/pybind11.h>

#include <stdexcept>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/version.hpp"

PYBIND11_MODULE(_spdfit, m) {
  m.doc() = "Compiled core of spdfit; use the `spdfit` package instead.";
  m.attr("__version__") = spdfit::kVersion;
  spdfit::python::bind_warning_class(m);
  spdfit::python::bind_io(m);
  spdfit::python::bind_noise(m);
  spdfit::python::bind_results(m);
  spdfit::python::bind_estimators(m);
  spdfit::python::bind_factor(m);
  spdfit::python::bind_linear_system(m);
  spdfit::python::bind_linkage(m);
  spdfit::python::bind_hexapod(m);
  spdfit::python::bind_physical(m);
  spdfit::python::bind_experiment(m);
  spdfit::python::bind_blas_core(m);
  spdfit::python::enable_every_protocol(m);  // after every pickled class is bound
  spdfit::python::bind_outcome(m);  // last: its exception translator is tried first
}
