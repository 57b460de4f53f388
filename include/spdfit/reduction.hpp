// The spectral quantities of A and B that several estimators share, computed once from
// the triangular factor.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <utility>

#include "spdfit/fit_options.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit {

class Reduction;

namespace detail {
template <int MaxN>
struct BasicReduction;
const BasicReduction<Eigen::Dynamic>& data_of(const Reduction& reduction);
Reduction reduce_with(const TriangularFactor& factor, const FitOptions& options, bool vectors_a);
Reduction reduction_of(std::shared_ptr<const BasicReduction<Eigen::Dynamic>> data);
}  // namespace detail

/// The data reduced to small matrices, all in the scaled units of the triangular factor: the SVD
/// of R11 (singular values of A, rank_a, cond_a) and the triangular factor R_b of B
/// ([R12; R22] = Q_b R_b, so B^T B = R_b^T R_b; singular values of B, rank_b).
///
/// Built by `reduce` in O(n^3) from a TriangularFactor, and read-only after that. Estimators
/// taking a Reduction are the careful path and let several methods share one factorization;
/// the overloads taking A and B call TriangularFactor::from_data and reduce. Copies share the
/// (immutable) data.
class Reduction {
 public:
  /// An empty reduction (m = n = 0); estimators throw std::invalid_argument on it.
  Reduction() = default;

  Eigen::Index m() const;       ///< rows (samples) accumulated
  Eigen::Index n() const;       ///< A's columns; X is n x d
  Eigen::Index d() const;       ///< B's columns (d = n: X square, as every method but ls and tls needs)
  Eigen::Index rank_a() const;  ///< numerical rank of A under the options' cut-off
  Eigen::Index rank_b() const;  ///< numerical rank of B
  const FitOptions& options() const;

 private:
  friend Reduction reduce(const TriangularFactor& factor, const FitOptions& options);
  friend Reduction detail::reduce_with(const TriangularFactor& factor, const FitOptions& options, bool vectors_a);
  friend const detail::BasicReduction<Eigen::Dynamic>& detail::data_of(const Reduction& reduction);
  friend Reduction detail::reduction_of(std::shared_ptr<const detail::BasicReduction<Eigen::Dynamic>> data);
  explicit Reduction(std::shared_ptr<const detail::BasicReduction<Eigen::Dynamic>> data) : data_(std::move(data)) {}

  std::shared_ptr<const detail::BasicReduction<Eigen::Dynamic>> data_;
};

/// Reduces the factor for the estimators. Throws std::invalid_argument when the factor has
/// fewer rows than columns (m < n) or the options are invalid. Cost O(n^3).
Reduction reduce(const TriangularFactor& factor, const FitOptions& options = {});

}  // namespace spdfit
