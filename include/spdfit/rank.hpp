// The numerical rank: one rule for every least-squares path (fit's rank_tolerance, solve's
// threshold, the linkage solves), as Eigen's setThreshold/rank() and NumPy's matrix_rank.
#pragma once

#include <Eigen/Core>
#include <string>

namespace spdfit {

/// The default relative cut-off for an m x n matrix: max(m, n) * machine epsilon, the editing
/// rule of the lecture notes (shared/seeds/002, section 3.8) and NumPy's matrix_rank.
double default_rank_tolerance(Eigen::Index rows, Eigen::Index cols);

/// The relative cut-off `tolerance` stands for: itself when >= 0, else the default.
double rank_cutoff(double tolerance, Eigen::Index rows, Eigen::Index cols);

/// True when `tolerance` is a usable relative cut-off: a number below 1 (negative for the
/// default); NaN and values >= 1 are not. Otherwise `error` (when given) says why, naming the
/// option `name` ("rank_tolerance", "threshold").
bool is_valid_rank_tolerance(double tolerance, const std::string& name, std::string* error = nullptr);

/// The number of singular values s_i (descending) with s_i > cutoff * s_1, strictly: a value
/// exactly at the cut-off counts as zero, as in NumPy's matrix_rank. Zero for an empty s or
/// s_1 == 0. Cost O(rank).
Eigen::Index numerical_rank(const Eigen::Ref<const Eigen::VectorXd>& s, double cutoff);

}  // namespace spdfit
