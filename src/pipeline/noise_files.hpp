// The files of a request's noise model (NoiseInputs) named in the errors about them: a size that
// does not fit the data is found only by the fit, whose error carries the option as its subject.
#pragma once

#include <string>
#include <utility>

#include "spdfit/fit_request.hpp"
#include "spdfit/io.hpp"

namespace spdfit::detail {

/// The file given for noise option `option` (library name: noise_cov_a, rest_a, ...), or empty.
inline const std::string& noise_file(const NoiseInputs& inputs, const std::string& option) {
  static const std::string none;
  if (option == "noise_cov_a") return inputs.cov_a.path;
  if (option == "noise_cov_b") return inputs.cov_b.path;
  if (option == "rest_a") return inputs.rest_a.path;
  if (option == "rest_b") return inputs.rest_b.path;
  return none;
}

/// fit() called; an error about the data of a noise option given as a file (its subject, an
/// InputError of Code::NoiseModel) becomes an io::DataError naming that file, with the same code.
template <typename Fit>
auto naming_noise_files(const NoiseInputs& inputs, Fit&& fit) -> decltype(fit()) {
  try {
    return std::forward<Fit>(fit)();
  } catch (const InputError& e) {
    const std::string& path = noise_file(inputs, e.subject());
    if (!path.empty()) throw io::DataError(path, 0, 0, e.what(), e.code());
    throw;
  }
}

}  // namespace spdfit::detail
