// The pieces of the _spdfit extension module, one function per area of the library.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>

#include "spdfit/fit_options.hpp"
#include "spdfit/method.hpp"

namespace spdfit::python {

/// The getter of a read-only attribute: a copy of the member, so that an Eigen member becomes a
/// NumPy array the caller owns and may write to (as NumPy's own results are), not pybind11's
/// read-only view into the C++ object (def_readonly).
template <typename Class, typename Member>
auto copied(Member Class::*member) {
  return [member](const Class& object) -> Member { return object.*member; };
}

/// The bootstrap's options of a Python call (None: the library's default).
struct BootstrapArgs {
  int replicates = 0;
  std::optional<double> confidence;
  std::optional<std::uint64_t> seed;
  unsigned threads = 0;
};

/// The FitOptions of a Python call, checked (std::invalid_argument, a ValueError, when invalid);
/// noise_ratio, max_iter and min_eig are refused for a `method` that does not take them, as the
/// CLI refuses --noise-ratio, --max-iter and --min-eig. None means the library's default.
FitOptions options_from(const std::optional<double>& rank_tolerance, const std::optional<double>& noise_ratio = {},
                        std::optional<Method> method = {}, const std::optional<int>& max_iter = {},
                        const std::optional<double>& min_eig = {}, const BootstrapArgs& boot = {});

/// The method a Python call names; std::invalid_argument (a ValueError) listing the methods for a
/// name that is none of them.
Method method_from(const std::string& name);

void bind_results(pybind11::module_& m);
void bind_estimators(pybind11::module_& m);
void bind_io(pybind11::module_& m);
void bind_linear_system(pybind11::module_& m);
void bind_linkage(pybind11::module_& m);
void bind_hexapod(pybind11::module_& m);
void bind_experiment(pybind11::module_& m);
void bind_factor(pybind11::module_& m);
void bind_blas_core(pybind11::module_& m);

}  // namespace spdfit::python
