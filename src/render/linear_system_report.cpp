// `spdfit solve`: a LinearSystemResult for people.
#include <sstream>

#include "spdfit/format.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

namespace {

std::string number(double value) { return format_number(value, Precision::Full); }

std::string vector_text(const Eigen::VectorXd& v) { return "[" + format_numbers(v, Precision::Full) + "]"; }

}  // namespace

std::string report(const LinearSystemResult& r) {
  std::ostringstream out;
  out << r.explanation << "\n\n";
  if (!r.ok()) out << "failed: " << r.message << "\n\n";
  out << "rank " << r.rank << ", nullity " << r.nullity << ", condition number " << number(r.condition_number)
      << " (reciprocal " << number(r.reciprocal_condition_number) << ")\n";
  out << "singular values: " << vector_text(r.singular_values) << "\n";
  out << "with unit-norm columns: " << vector_text(r.scaled_singular_values) << ", condition number "
      << number(r.scaled_condition_number) << " (the rank's cut-off: " << number(r.rank_tolerance) << " * sigma_max)\n";
  out << "finite solutions: dimension " << r.finite_solution_dimension << "; at infinity: dimension "
      << r.at_infinity_dimension << " (-1: none)\n";
  for (Eigen::Index j = 0; j < r.p && j < r.solution.cols(); ++j) {
    const auto column = static_cast<std::size_t>(j);
    out << (r.columns[column].consistent ? "solution" : "least-squares solution")
        << (r.nullity > 0 ? " (minimum norm)" : "");
    if (r.p > 1) out << " for right-hand side " << j + 1;
    out << ": x = " << vector_text(r.solution.col(j)) << ", residual norm "
        << number(r.columns[column].residual_norm) << "\n";
  }
  out << "null space basis:" << (r.nullity == 0 ? " none" : "") << "\n";
  for (Eigen::Index j = 0; j < r.null_space.cols(); ++j) out << "  " << vector_text(r.null_space.col(j)) << "\n";
  out << "range basis:" << (r.rank == 0 ? " none" : "") << "\n";
  for (Eigen::Index j = 0; j < r.range.cols(); ++j) out << "  " << vector_text(r.range.col(j)) << "\n";
  return out.str();
}

}  // namespace spdfit
