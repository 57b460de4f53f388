// FitOptions' own check, in plain C++ (the option table, a layer above, spells the same ranges for
// the front ends; a unit test checks that the two agree).
#include "spdfit/fit_options.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace spdfit {

namespace {

bool finite(double v) { return std::abs(v) <= std::numeric_limits<double>::max(); }

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

// The shortest text that reads back as `value`, as messages about option values print it.
std::string number(double value) {
  if (value == std::floor(value) && std::abs(value) < 1e15) return std::to_string(static_cast<long long>(value));
  char buffer[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace

bool FitOptions::is_valid(std::string* error) const {
  if (rank_tolerance && !(finite(*rank_tolerance) && *rank_tolerance >= 0.0 && *rank_tolerance < 1.0)) {
    return fail(error, "`rank_tolerance` must be a number in [0, 1), got " + number(*rank_tolerance));
  }
  if (!(finite(noise_ratio) && noise_ratio > 0.0)) return fail(error, "`noise_ratio` must be a finite number > 0, got " + number(noise_ratio));
  if (noise && noise_ratio != 1.0) {
    return fail(error, "`noise_ratio` cannot be combined with a noise model (" + noise->option_a() + ", " +
                           noise->option_b() + "): the noise model gives the noise in A and in B, and so their ratio");
  }
  if (max_iterations < 1 || max_iterations > 1000000) {
    return fail(error, "`max_iterations` must be an integer in [1, 1000000], got " + std::to_string(max_iterations));
  }
  if (!(finite(min_eig) && min_eig >= 0.0)) return fail(error, "`min_eig` must be a finite number >= 0, got " + number(min_eig));
  if (bootstrap < 0 || bootstrap > 10000000) return fail(error, "`bootstrap` must be an integer in [0, 10000000], got " + std::to_string(bootstrap));
  if (!(confidence > 0.0 && confidence < 1.0)) {
    return fail(error, "`confidence` must be a fraction strictly between 0 and 1, got " + number(confidence));
  }
  if (threads > 1024) return fail(error, "`threads` must be an integer in [0, 1024], got " + std::to_string(threads));
  return true;
}

}  // namespace spdfit
