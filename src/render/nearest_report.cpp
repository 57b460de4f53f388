// A repair's result for people (Python's repr of a NearestResult).
#include <cmath>
#include <sstream>

#include "spdfit/format.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

std::string report(const NearestResult& r) {
  std::ostringstream out;
  out << "nearest matrix (" << r.X.rows() << " x " << r.X.cols() << "), at distance "
      << format_number(r.distance, Precision::Full) << " from the input; " << r.clipped
      << " eigenvalue(s) at the floor " << format_number(r.min_eig, Precision::Full)
      << " (the input's smallest: " << format_number(r.min_eigenvalue_before, Precision::Full) << ")\n";
  if (r.iterations > 0) {
    out << "Newton: " << r.iterations << " iterations, ||diag(X) - d||_2 = "
        << format_number(r.gradient_norm, Precision::Brief) << (r.converged ? ", converged" : ", not converged")
        << "\n";
  }
  if (!r.method.empty()) out << "method: " << r.method << "\n";
  if (r.fixed_entries > 0) out << r.fixed_entries << " entries kept exactly\n";
  if (!std::isnan(r.lower_bound)) {
    out << "lower bound on the distance: " << format_number(r.lower_bound, Precision::Full) << " (gap "
        << format_number(r.distance - r.lower_bound, Precision::Brief) << ")\n";
  }
  if (!std::isnan(r.optimality_residual)) {
    out << "optimality residual: " << format_number(r.optimality_residual, Precision::Brief) << "\n";
  }
  for (const NearestStart& s : r.starts) {
    out << "start " << s.name << ": distance " << format_number(s.distance, Precision::Full) << " after "
        << s.iterations << " iterations\n";
  }
  out << "Cholesky factorization: " << (r.cholesky_ok ? "yes" : "no") << "\n";
  if (r.X.size() > 0) out << format_side_by_side({"X"}, {r.X});
  if (r.F.size() > 0) out << format_side_by_side({"F"}, {r.F});
  return out.str();
}

}  // namespace spdfit
