// _spdfit: the compiled half of the spdfit Python package (python/spdfit/__init__.py is the
// public face; it turns warnings into Python warnings and failures into exceptions).
#include <pybind11/pybind11.h>

#include <stdexcept>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/options.hpp"
#include "spdfit/version.hpp"

PYBIND11_MODULE(_spdfit, m) {
  m.doc() = "Compiled core of spdfit; use the `spdfit` package instead.";
  m.attr("__version__") = spdfit::kVersion;
  spdfit::python::bind_io(m);
  spdfit::python::bind_noise(m);
  spdfit::python::bind_results(m);
  spdfit::python::bind_estimators(m);
  spdfit::python::bind_factor(m);
  spdfit::python::bind_linear_system(m);
  spdfit::python::bind_linkage(m);
  spdfit::python::bind_hexapod(m);
  spdfit::python::bind_physical(m);
  spdfit::python::bind_payload(m);
  spdfit::python::bind_experiment(m);
  spdfit::python::bind_blas_core(m);
  spdfit::python::enable_every_protocol(m);  // after every pickled class is bound
  // The library's messages name options by their library names in backticks (OptionError and
  // other misuse): Python says them with its own keywords, as a ValueError.
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, spdfit::spell_options(e.what(), spdfit::Frontend::Python).c_str());
    }
  });
}
