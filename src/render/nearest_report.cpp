// A repair's result for people (Python's repr of a NearestResult).
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
  out << "Cholesky factorization: " << (r.cholesky_ok ? "yes" : "no") << "\n"
      << format_side_by_side({"X"}, {r.X});
  return out.str();
}

}  // namespace spdfit
