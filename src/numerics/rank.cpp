#include "spdfit/rank.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spdfit {

double default_rank_tolerance(Eigen::Index rows, Eigen::Index cols) {
  return static_cast<double>(std::max(rows, cols)) * std::numeric_limits<double>::epsilon();
}

double rank_cutoff(double tolerance, Eigen::Index rows, Eigen::Index cols) {
  return tolerance >= 0.0 ? tolerance : default_rank_tolerance(rows, cols);
}

bool is_valid_rank_tolerance(double tolerance, const std::string& name, std::string* error) {
  if (std::isnan(tolerance) || !(tolerance < 1.0)) {
    if (error) *error = name + " must be a number below 1 (negative for the default max(m, n) * eps)";
    return false;
  }
  return true;
}

Eigen::Index numerical_rank(const Eigen::Ref<const Eigen::VectorXd>& s, double cutoff) {
  if (s.size() == 0 || !(s(0) > 0.0)) return 0;
  const double threshold = cutoff * s(0);
  Eigen::Index rank = 0;
  while (rank < s.size() && s(rank) > threshold) ++rank;
  return rank;
}

}  // namespace spdfit
