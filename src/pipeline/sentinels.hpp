// Internal: values no sensor measures, which loggers write for an invalid reading (9.9e37, 1e38):
// one of them decides a fit, its singular values and its ranks, so the rows holding them are named.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/row_numbers.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// The magnitude from which a value is a logger's code, not a measurement: no quantity a fit's
/// user logs reaches it in any unit, and loggers' "invalid" codes (9.9e37, FLT_MAX) are above it.
constexpr double kSentinelMagnitude = 1e30;

/// The rows (0-based, ascending) of A and B (when B has A's rows) holding a value of magnitude
/// kSentinelMagnitude or more. Cost O(m (n + d)).
std::vector<Eigen::Index> sentinel_rows(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B);

/// The warning about the rows of A and B (m rows each, numbered as in their files by `numbers`)
/// holding a value of magnitude kSentinelMagnitude or more, naming up to five with their values and
/// column, and the rows to keep; nothing when there is none. `robust`: the fit was robust, which
/// gives such rows weight 0 (robust/m_estimator.cpp), and the warning says so instead. Cost
/// O(m (n + d)).
std::optional<Warning> sentinel_warning(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B, const RowNumbers& numbers = {},
                                        bool robust = false);

/// The streamed fit's form of sentinel_warning (no rows kept to name): the warning when the factor
/// of the pass (its scale exponents: a magnitude of 2^99, 6e29, or more) holds such a value, naming
/// the in-memory fit that names the rows. Nothing otherwise. O(1).
std::optional<Warning> streamed_sentinel_warning(const TriangularFactor& factor);

/// What a failed fit's message gains when the data hold such values: they, not the data, decided it.
inline const std::string& sentinel_failure_note() {
  static const std::string note =
      " (the data hold values of magnitude 1e30 or more, which decide this: see the warnings)";
  return note;
}

}  // namespace spdfit::detail
