// Internal: the mean and the centered sum of squares of rows arriving a block at a time, merged
// stably, for the covariances of a noise model's rest rows.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "spdfit/noise_model.hpp"

namespace spdfit::detail {

/// The mean and M2 = sum_i (x_i - mean)(x_i - mean)^T of the rows seen so far. Each block is
/// centered about its own mean before its squares are summed, and blocks merge by Chan, Golub and
/// LeVeque's update (M2 = M2_a + M2_b + delta delta^T n_a n_b / n, delta the difference of the
/// means), so that a large constant offset (a static load) costs no accuracy, as the textbook
/// sum of squares minus N mean^2 would. Cost O(k c^2) per block of k rows and c columns.
class RowMoments {
 public:
  /// Adds the rows of `block` (k x c, finite; c fixed by the first block).
  void add(const Eigen::Ref<const Eigen::MatrixXd>& block);

  std::uint64_t rows() const { return rows_; }
  const Eigen::VectorXd& mean() const { return mean_; }
  /// The sample covariance M2 / (N - 1), exactly symmetric; needs N >= 2.
  Eigen::MatrixXd covariance() const;

  /// A value of magnitude kSentinelMagnitude or more (a logger's code for an invalid reading):
  /// its row (0-based, counted over every block) and column.
  struct Sentinel {
    std::uint64_t row;
    Eigen::Index column;
    double value;
  };
  /// The first few such values (one per row), and how many rows hold one.
  const std::vector<Sentinel>& sentinels() const { return sentinels_; }
  std::uint64_t sentinel_rows() const { return sentinel_rows_; }

 private:
  std::vector<Sentinel> sentinels_;
  std::uint64_t sentinel_rows_ = 0;
  std::uint64_t rows_ = 0;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd m2_;
};

/// NoiseModel::from_rest of a log's rest segment (FitRequest::rest_rows): its messages and
/// option_a() and option_b() name `rest_rows`, not `rest_a` and `rest_b`, which the user did not
/// give. Throws InputError (subject rest_rows) as from_rest does.
struct LogRestRows {
  static NoiseModel from_rest(const Eigen::Ref<const Eigen::MatrixXd>& rest_a,
                              const Eigen::Ref<const Eigen::MatrixXd>& rest_b);
};

}  // namespace spdfit::detail
