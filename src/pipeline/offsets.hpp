// Internal: FitOptions::offsets, the constant offsets in the data's columns, applied the same way
// to data in memory, to a streamed factor and to the bootstrap's resamples; and the warnings for
// data whose offsets a fit without them would take for signal.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// Offsets::Rest's tare: the means of the rest rows the noise model was made from, resolved to n
/// and d columns (in the units the model is in). OptionError (Code::OptionConflict, naming
/// `offsets`) when the options have no noise model from rest rows.
struct Tare {
  Eigen::VectorXd a, b;
  /// FitResult::offsets of a fit of the tared data.
  FitOffsets offsets() const { return FitOffsets{Offsets::Rest, {}, a, b}; }
};
Tare rest_tare(const FitOptions& options, Eigen::Index n, Eigen::Index d);

/// The data with rest_tare subtracted from every row (for a fit in memory with Offsets::Rest).
struct TaredData {
  Tare tare;
  Eigen::MatrixXd A, B;
};
TaredData tared_data(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                     const FitOptions& options);

/// The offsets c = mu_B - X^T mu_A of the intercept factor's means (d numbers); empty when the
/// factor has no intercept (or no rows) or X is not n x d.
Eigen::VectorXd intercept_offsets(const TriangularFactor& factor, const Eigen::MatrixXd& X);

/// The factor of [A B] with the tare subtracted from every row, from the factor of [1 A B] of the
/// rows as read (`centred`: intercept() true): the QR of [R_c; sqrt(m) (mu - tare)^T], R_c the
/// centred rows' factor and mu their means, as exact as factoring the tared rows (a streamed, a
/// distributed and a resampled fit tared after the pass). O((n + d)^3).
TriangularFactor tared_factor(const TriangularFactor& centred, const Tare& tare);

/// The options the estimators see once the tare is subtracted (offsets Rest: None).
FitOptions options_after_tare(const FitOptions& options);

/// FitResult::offsets for a fit with `options`: Estimate, c = mu_B - X^T mu_A from the intercept
/// factor's means (nothing when the fit failed); Rest, the tare. Nothing for None.
std::optional<FitOffsets> offsets_of(const FitResult& result, const TriangularFactor& factor, const FitOptions& options,
                                     const Tare* tare);

/// The warnings for a fit without offsets (Offsets::None) of A and B (in the units fitted): the
/// intercept of least squares with one (B ~= A X + 1 c^T) more than kOffsetStandardErrors
/// standard errors from 0 and changing X by more than kOffsetShift of X's standard errors (naming
/// `offsets` estimate); and, with a noise model from rest rows, B's rest
/// means far from 0 while the data's means are the same (untared forces, naming `offsets` rest;
/// then nothing else). Without `say_untared` untared data get no warning here (a caller whose own
/// fit says it: the hexapod's physical fit). `plain`: the factor of [A B] when the caller has it
/// (the centred one is then a downdate of it); null: the factor of [1 A B] is made here, one pass
/// over the rows, and the plain one from it.
std::vector<Warning> offset_warnings(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::MatrixXd>& B, const TriangularFactor* plain,
                                     const FitOptions& options, bool say_untared = true);

/// offset_warnings for data as given, with `options`' units (FitOptions::scale_a, scale_b) applied
/// first: for a workflow that runs several fits on the same data (compare) and warns once.
std::vector<Warning> offset_warnings_as_given(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                              const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options);

/// The columns of B that look untared ("B's column 2: 21 at rest, 20.9 in the data"), empty when
/// none: the rest rows' mean more than kOffsetStandardErrors standard errors (rest_var / rest_rows)
/// from 0, and the data's column mean within as many standard errors of it. Shared by the fit's
/// warning and the hexapod's physical fit's.
std::string untared_columns(const Eigen::Ref<const Eigen::MatrixXd>& B, const Eigen::VectorXd& rest_mean,
                            const Eigen::VectorXd& rest_variance, std::uint64_t rest_rows);

/// How far (in standard errors) an offset must be from 0 to be warned about.
inline constexpr double kOffsetStandardErrors = 5.0;
/// How far (in X's standard errors) an offset must move X to be warned about.
inline constexpr double kOffsetShift = 2.0;

}  // namespace spdfit::detail
