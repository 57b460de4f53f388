// Numbers as text for people: the one formatter behind every report, table and message, with
// its precisions named by purpose.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace spdfit {

/// Significant digits of a number shown to people, by purpose (C's "%.Ng").
enum class Precision {
  Brief = 3,   ///< messages and prose: "cond(A) = 1.25e+03", "a floor of 1e-08"
  Medium = 4,  ///< explanations and levels: "the 95% interval", "singular values 3.162, 0.01"
  Full = 6,    ///< tables of results a reader compares or copies: "2.74949", "0.817564"
};

/// `value` in `precision` significant digits, as C's "%.Ng" writes it: "1.5e+08", "0.001",
/// "inf", "-inf", "nan". Cost O(1).
std::string format_number(double value, Precision precision = Precision::Brief);

/// `value` with `decimals` digits after the point ("%.*f"), in scientific notation ("%.*e") from
/// |value| >= 1e5 on, so that a column of ordinary numbers lines up and a huge one stays short;
/// "-" for NaN. decimals in [0, 17].
std::string format_fixed(double value, int decimals = 4);

/// Decimals for an estimate printed beside its standard error and interval, so that whether a
/// value lies inside the interval can be read: down to the standard error's third significant
/// digit (its first and two more), "12.4788 +- 0.0118   [12.4600, 12.4974]". 4 where the
/// standard error is missing, zero or not finite; in [0, 12].
int interval_decimals(double standard_error);

/// The values in `precision` significant digits, separated by ", ": "1.5, -2, 0.25" (empty for
/// none). Messages and reports put lists of numbers this way.
std::string format_numbers(const Eigen::VectorXd& values, Precision precision = Precision::Brief);

/// A fraction as a percentage in `precision` significant digits: "95%" for 0.95, "2.5%" for 0.025.
std::string format_percent(double fraction, Precision precision = Precision::Brief);

/// Matrices printed side by side under their titles, each entry with `digits` decimals (fixed
/// point when a matrix's largest entry is in [1e-2, 1e5), scientific otherwise), as many blocks
/// to a line as fit in `width` columns; no spaces at the ends of lines. titles and matrices have
/// the same length.
std::string format_side_by_side(const std::vector<std::string>& titles, const std::vector<Eigen::MatrixXd>& matrices,
                                int digits = 4, std::size_t width = 120);

}  // namespace spdfit
