// The covariance files of a request's noise model (NoiseInputs::cov_a, cov_b) named in the errors
// about them: a size that does not fit the data is found only by the fit, whose message names
// the option.
#pragma once

#include <string>
#include <utility>

#include "spdfit/fit_request.hpp"
#include "spdfit/io.hpp"

namespace spdfit::detail {

/// fit() called; an OptionError about `noise_cov_a` or `noise_cov_b` given as a file becomes an
/// io::DataError naming that file (with the option in its message).
template <typename Fit>
auto naming_noise_files(const NoiseInputs& inputs, Fit&& fit) -> decltype(fit()) {
  try {
    return std::forward<Fit>(fit)();
  } catch (const OptionError& e) {
    const std::string message = e.what();
    for (const auto& [option, path] : {std::pair<std::string, const std::string*>{"`noise_cov_a`", &inputs.cov_a},
                                       std::pair<std::string, const std::string*>{"`noise_cov_b`", &inputs.cov_b}}) {
      if (!path->empty() && message.find(option) != std::string::npos) throw io::DataError(*path, 0, 0, message);
    }
    throw;
  }
}

}  // namespace spdfit::detail
