// The BLAS-core check (src/numerics/blas_core.hpp) for the import-time warning of
// python/spdfit/_blas_core.py: the module cannot restart itself as the CLI does.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "spdfit/blas.hpp"

namespace py = pybind11;

namespace spdfit::python {

void bind_blas_core(py::module_& m) {
  m.def(
      "blas_core",
      [] {
        const BlasCoreCheck check = check_blas_core();
        py::dict result;
        result["core"] = blas_core_name();
        result["reported"] = check.reported;
        result["from_test_switch"] = check.from_test_switch;
        result["cpu"] = check.cpu;
        result["user_coretype"] = check.user_coretype;
        result["suggested"] = check.suggested;
        return result;
      },
      "Which kernels OpenBLAS runs ('core'; '' when the BLAS is not OpenBLAS), the core spdfit takes "
      "it to have reported ('reported': 'core', or SPDFIT_TEST_BLAS_CORE's value, and then "
      "'from_test_switch'), the CPU's widest vector extension ('cpu': 'AVX-512', 'AVX2' or ''), the "
      "user's OPENBLAS_CORETYPE ('user_coretype') and the OPENBLAS_CORETYPE to set for faster "
      "kernels ('suggested'; '' when nothing needs changing).");
}

}  // namespace spdfit::python
