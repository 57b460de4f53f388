// Option validators with messages a person can act on (CLI11's numeric ranges print the
// largest double in full).
#pragma once

#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "spdfit/rank.hpp"

namespace spdfit::cli {

/// A finite number >= 0.
inline CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && value >= 0.0) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number >= 0";
      },
      "NUMBER >= 0");
}

/// A finite number > 0.
inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && value > 0.0) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number > 0";
      },
      "NUMBER > 0");
}

/// A relative rank cut-off given on the command line: a finite number >= 0 that the library's
/// one rule accepts (spdfit::is_valid_rank_tolerance: below 1), so that every such option is a
/// usage error (exit 2) on the same values.
inline CLI::Validator rank_tolerance() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && value >= 0.0 && is_valid_rank_tolerance(value, "")) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a number in [0, 1)";
      },
      "NUMBER in [0, 1)");
}

}  // namespace spdfit::cli
