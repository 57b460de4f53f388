// Hostile numerical data for the stress tests: random problems over many sizes, condition
// numbers and scales, with zero columns, exact and near singularity and denormal entries, and
// helpers that bring data of any scale to order one so that defining equations can be checked
// without overflow.
#pragma once

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "test_support.hpp"

namespace spdfit::test {

/// The smallest positive normal double; entries below it are denormal.
inline constexpr double kMinNormal = std::numeric_limits<double>::min();

/// The spacing of the doubles below kMinNormal (2^-1074): no answer can be closer than this
/// to an exact value that is denormal or underflows.
inline constexpr double kDenormalStep = std::numeric_limits<double>::denorm_min();

/// A number for a test's trace ("1e-150", "3.2e+12").
inline std::string format(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

/// One stress problem: A X ~= B with A and B m x n.
struct StressCase {
  std::string name;
  MatrixXd A, B;
};

/// What is done to a well-behaved problem to make it hostile.
enum class Hostility {
  kNone,              ///< cond(A) as asked, nothing else
  kZeroColumnA,       ///< a column of A is zero (exactly rank-deficient A)
  kZeroColumnB,       ///< a column of B is zero (rank-deficient B)
  kDuplicateColumnA,  ///< two equal columns of A (exactly singular, nonzero columns)
  kRankOneB,          ///< B of rank one
  kNearlySingularA,   ///< cond(A) = 1e15..1e17, at the edge of double precision
  kDenormalEntries,   ///< a few entries of A and B replaced by denormal numbers
  kDenormalData,      ///< every entry of A (or B) denormal
  kAllZero,           ///< A and B zero
};

inline const char* to_string(Hostility h) {
  switch (h) {
    case Hostility::kNone: return "plain";
    case Hostility::kZeroColumnA: return "zero column in A";
    case Hostility::kZeroColumnB: return "zero column in B";
    case Hostility::kDuplicateColumnA: return "duplicate column in A";
    case Hostility::kRankOneB: return "B of rank one";
    case Hostility::kNearlySingularA: return "nearly singular A";
    case Hostility::kDenormalEntries: return "denormal entries";
    case Hostility::kDenormalData: return "denormal data";
    case Hostility::kAllZero: return "all zero";
  }
  return "?";
}

inline const std::vector<Hostility>& all_hostilities() {
  static const std::vector<Hostility> all = {
      Hostility::kNone,     Hostility::kZeroColumnA,     Hostility::kZeroColumnB,
      Hostility::kDuplicateColumnA, Hostility::kRankOneB, Hostility::kNearlySingularA,
      Hostility::kDenormalEntries,  Hostility::kDenormalData, Hostility::kAllZero};
  return all;
}

/// A noisy problem B = A X0 + noise with cond(A) = `cond`, X0 SPD with condition number up to
/// 1e4, then made hostile and scaled: A by scale_a, B by scale_b.
inline StressCase make_stress_case(Generator& g, Index m, Index n, double cond, Hostility hostility, double scale_a,
                                   double scale_b) {
  StressCase c;
  c.name = "m " + std::to_string(m) + ", n " + std::to_string(n) + ", cond " + format(cond) + ", " +
           to_string(hostility) + ", scales " + format(scale_a) + " / " + format(scale_b);
  const double condition = hostility == Hostility::kNearlySingularA ? std::pow(10.0, g.uniform(15, 17)) : cond;
  c.A = g.with_condition(m, n, condition);
  const MatrixXd X0 = g.spd(n, std::pow(10.0, g.uniform(0, 4)));
  c.B = c.A * X0 + 1e-3 * g.gaussian(m, n);
  const Index j = static_cast<Index>(g.uniform(0, static_cast<double>(n)));
  switch (hostility) {
    case Hostility::kZeroColumnA:
      c.A.col(j).setZero();
      break;
    case Hostility::kZeroColumnB:
      c.B.col(j).setZero();
      break;
    case Hostility::kDuplicateColumnA:
      if (n > 1) c.A.col(j) = c.A.col((j + 1) % n);
      else c.A.setZero();
      break;
    case Hostility::kRankOneB:
      c.B = g.gaussian(m, 1) * g.gaussian(1, n);
      break;
    case Hostility::kDenormalEntries:
      for (int k = 0; k < 3; ++k) {
        c.A(static_cast<Index>(g.uniform(0, static_cast<double>(m))), j) = g.uniform(-1, 1) * 1e-310;
        c.B(static_cast<Index>(g.uniform(0, static_cast<double>(m))), j) = g.uniform(-1, 1) * 1e-315;
      }
      break;
    case Hostility::kAllZero:
      c.A.setZero();
      c.B.setZero();
      break;
    case Hostility::kNone:
    case Hostility::kNearlySingularA:
    case Hostility::kDenormalData:
      break;
  }
  c.A *= scale_a;
  c.B *= scale_b;
  if (hostility == Hostility::kDenormalData) {
    // Scaled after the rest, so that the data really is denormal whatever the scales.
    (g.uniform(0, 1) < 0.5 ? c.A : c.B) *= 1e-310 / std::max(c.A.cwiseAbs().maxCoeff(), kMinNormal);
  }
  return c;
}

/// The exponent e with 2^-e X of largest entry in [0.5, 1) (0 for a zero matrix): dividing by
/// 2^e is exact, so the scaled problem is the same problem in other units.
inline int unit_exponent(const MatrixXd& X) {
  const double biggest = X.size() ? X.cwiseAbs().maxCoeff() : 0.0;
  if (!(biggest > 0.0)) return 0;
  int e = 0;
  std::frexp(biggest, &e);
  return e;
}

/// X 2^e entry by entry (exact bar overflow and underflow, also for denormal entries).
inline MatrixXd scaled_by_power_of_two(const MatrixXd& X, int e) {
  return X.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

/// The problem A X = B in units where A and B have largest entries of order one: a = A 2^-ea,
/// b = B 2^-eb, x = X 2^(ea - eb), so that a x - b = (A X - B) 2^-eb. x_step is the spacing of
/// the denormal doubles in these units: an X whose exact value is that small (B tiny against A)
/// can only be rounded to a multiple of it, so checks of x allow ||a||^2 sqrt(size) x_step more.
struct UnitProblem {
  MatrixXd a, b, x;
  double x_step = 0.0;

  /// ||a|| ||dx|| with every entry of x off by up to one step.
  double representation_error() const {
    return a.norm() * std::sqrt(static_cast<double>(x.size())) * x_step;
  }
};

inline UnitProblem in_units(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X) {
  const int ea = unit_exponent(A), eb = unit_exponent(B);
  return {scaled_by_power_of_two(A, -ea), scaled_by_power_of_two(B, -eb), scaled_by_power_of_two(X, ea - eb),
          std::ldexp(kDenormalStep, ea - eb)};
}

/// No NaN anywhere and no Inf either (for answers).
inline bool all_finite(const MatrixXd& X) { return X.allFinite(); }

/// Not NaN (diagnostics may be +inf where documented, e.g. the condition number of singular data).
inline bool not_nan(double x) { return !std::isnan(x); }

}  // namespace spdfit::test
