// Option validators with messages a person can act on (CLI11's numeric ranges print the
// largest double in full).
#pragma once

#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "spdfit/nearest_spd.hpp"
#include "spdfit/rank.hpp"

namespace spdfit::cli {

/// A number option whose value must pass `accepts`; otherwise "'TEXT' is not a <what>".
template <typename Accepts>
CLI::Validator number_validator(Accepts accepts, const std::string& what, const std::string& shown) {
  return CLI::Validator(
      [accepts, what](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && accepts(value)) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a " + what;
      },
      shown);
}

/// An integer in [lo, hi]: "'2.5' is not an integer in [1, 100000000]" (CLI11's range says only
/// that 2.5 is out of range, or that the arguments were not expected).
inline CLI::Validator integer_in(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const long long value = std::stoll(text, &used);
          if (used == text.size() && value >= lo && value <= hi) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not an integer in " + range;
      },
      "INTEGER in " + range);
}

/// A finite number >= 0.
inline CLI::Validator non_negative() {
  return number_validator([](double v) { return std::isfinite(v) && v >= 0.0; }, "finite number >= 0",
                          "NUMBER >= 0");
}

/// A finite number > 0.
inline CLI::Validator positive() {
  return number_validator([](double v) { return std::isfinite(v) && v > 0.0; }, "finite number > 0",
                          "NUMBER > 0");
}

/// A fraction strictly between 0 and 1 (a confidence level).
inline CLI::Validator open_fraction() {
  return number_validator([](double v) { return v > 0.0 && v < 1.0; }, "fraction strictly between 0 and 1",
                          "FRACTION in (0, 1)");
}

/// A relative rank cut-off given on the command line: a number >= 0 that the library's one rule
/// accepts (spdfit::is_valid_rank_tolerance: below 1), so that every such option is a usage error
/// (exit 2) on the same values.
inline CLI::Validator rank_tolerance() {
  return number_validator([](double v) { return v >= 0.0 && is_valid_rank_tolerance(v, ""); },
                          "number in [0, 1)", "NUMBER in [0, 1)");
}

/// A relative eigenvalue floor as the library's rule accepts it (EigenvalueFloor::is_valid: [0, 1)).
inline CLI::Validator relative_floor() {
  return number_validator([](double v) { return EigenvalueFloor::relative_to_largest(v).is_valid(); },
                          "number in [0, 1)", "NUMBER in [0, 1)");
}

}  // namespace spdfit::cli
