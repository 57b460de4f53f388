// The noise in A and B: the covariance of the noise in each row of A and of B, given as standard
// deviations, as covariance matrices, or measured from rows recorded with the machine at rest.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/outcome.hpp"
#include "spdfit/io.hpp"

namespace spdfit {

namespace detail {
class RowMoments;
struct NoiseModelJson;
struct LogRestRows;
}

/// Where a noise model's covariances come from.
enum class NoiseSource {
  Std,   ///< standard deviations, one per side or one per column
  Cov,   ///< covariance matrices
  Rest,  ///< the sample covariances of rows recorded at rest
};

/// "std", "cov" or "rest": the noise model's source in reports (a fit without a noise model
/// reports "assumed-equal").
constexpr std::string_view to_string(NoiseSource source) {
  switch (source) {
    case NoiseSource::Std:
      return "std";
    case NoiseSource::Cov:
      return "cov";
    case NoiseSource::Rest:
      return "rest";
  }
  return "unknown";
}

/// The errors-in-variables model of A X ~= B: the rows a_i of A (n columns) and b_i of B (d
/// columns) are measured as a_i = a0_i + e_i, b_i = b0_i + f_i with a0_i X = b0_i, and the noise
/// e_i, f_i is independent from row to row and between A and B, zero-mean, with covariances
/// Sigma_A (n x n) and Sigma_B (d x d), symmetric positive semidefinite and the same for every
/// row. Then the residual r_i = (a_i X - b_i)^T has covariance X^T Sigma_A X + Sigma_B, and the
/// maximum-likelihood estimate minimizes sum_i r_i^T (X^T Sigma_A X + Sigma_B)^-1 r_i.
///
/// Made by one of the factories below (FitOptions::noise takes it); every factory validates its
/// input and throws OptionError (options.hpp, a std::invalid_argument) naming the option by its
/// library name in backticks (`noise_std_a`, `noise_cov_b`, `rest_a`, ...), or io::DataError
/// naming a rest file. Below, "std::invalid_argument" is that OptionError. A model is
/// immutable. One given by one standard deviation per side is completed to n x n and d x d
/// covariances when it meets the data (resolved).
class NoiseModel {
 public:
  /// Standard deviations of the noise in A and B, in the data's units: each vector holds one
  /// value for every column (Sigma = diag(std^2)), or a single value for all of that side's
  /// columns; 0 means exact (that side or column has no noise). Throws std::invalid_argument
  /// (naming `noise_std_a` or `noise_std_b`) for an empty vector, a negative, NaN or infinite
  /// value.
  static NoiseModel from_std(const Eigen::VectorXd& std_a, const Eigen::VectorXd& std_b);
  /// One standard deviation for every column of A, one for every column of B.
  static NoiseModel from_std(double std_a, double std_b);

  /// Full covariances, n x n for A and d x d for B. Throws std::invalid_argument (naming
  /// `noise_cov_a` or `noise_cov_b`) for a matrix that is empty, not square, not finite, not
  /// symmetric (beyond 1e-10 of its largest entry) or not positive semidefinite (an eigenvalue
  /// below -64 n eps times the largest). The symmetric part is kept.
  static NoiseModel from_cov(const Eigen::MatrixXd& cov_a, const Eigen::MatrixXd& cov_b);

  /// The sample covariances (divisor N - 1, about the rows' own means, so that a constant load
  /// is not noise) of N rows of A and N rows of B recorded with the machine at rest: true
  /// accelerations zero, forces constant. Computed stably (block means merged with Chan's
  /// update, no sums of squares). Throws std::invalid_argument (naming `rest_a` or `rest_b`) when
  /// a side has fewer than 2 rows, the row counts differ, or a value is NaN or infinite. Warnings
  /// (warnings()): fewer than 10 rows per column (the covariance is too uncertain to trust), or a
  /// column of the rest rows of A whose mean is more than 3 standard deviations from zero (the
  /// machine perhaps not at rest). Cost O(N (n^2 + d^2)).
  static NoiseModel from_rest(const Eigen::Ref<const Eigen::MatrixXd>& rest_a,
                              const Eigen::Ref<const Eigen::MatrixXd>& rest_b);
  /// from_rest with the rows in files (any format io::RowReader reads), streamed `block_rows`
  /// at a time in O(block_rows (n + d) + n^2 + d^2) memory. Throws io::DataError naming the file
  /// for bad data, too few rows, or row counts that differ; std::invalid_argument when
  /// block_rows < 1. With two column selections in read.columns (A's and B's in one log, as
  /// FitRequest::a_cols and b_cols give them), rest_a_path is read with the first and rest_b_path
  /// with the second (the same file may be both).
  static NoiseModel from_rest_files(const std::string& rest_a_path, const std::string& rest_b_path,
                                    const io::ReadOptions& read = {}, Eigen::Index block_rows = Eigen::Index{1} << 15);

  NoiseSource source() const { return source_; }

  /// Sigma_A (n x n) and Sigma_B (d x d); empty (0 x 0) for one standard deviation per side until
  /// the model is resolved.
  const Eigen::MatrixXd& cov_a() const { return cov_a_; }
  const Eigen::MatrixXd& cov_b() const { return cov_b_; }
  /// Whether cov_a() and cov_b() are set (every source but one standard deviation per side).
  bool is_resolved() const { return cov_a_.size() > 0 && cov_b_.size() > 0; }

  /// The standard deviations as given (source Std; empty otherwise).
  const Eigen::VectorXd& std_a() const { return std_a_; }
  const Eigen::VectorXd& std_b() const { return std_b_; }

  /// Source Rest: the number of rest rows N and the rest rows' means (the mean of B is the static
  /// load); nothing and empty otherwise.
  std::optional<std::uint64_t> rest_rows() const { return rest_rows_; }
  const Eigen::VectorXd& rest_mean_a() const { return rest_mean_a_; }
  const Eigen::VectorXd& rest_mean_b() const { return rest_mean_b_; }
  /// Source Rest from files: their paths (empty for rows given in memory).
  const std::string& rest_a_path() const { return rest_a_path_; }
  const std::string& rest_b_path() const { return rest_b_path_; }

  /// What the factory found for the user to know (see from_rest); every fit with this model
  /// repeats them in its warnings.
  const std::vector<Warning>& warnings() const { return warnings_; }

  /// The library names of the options that gave Sigma_A and Sigma_B, in backticks as messages
  /// use them: "`noise_std_a`", "`noise_cov_a`" or "`rest_a`" (and the same for B); "`rest_rows`"
  /// for both when the rest rows are rows of the fitted log (FitRequest::rest_rows).
  std::string option_a() const;
  std::string option_b() const;

  /// Sigma_A == 0 (every entry exactly zero: A exact), and whether Sigma_A, Sigma_B are positive
  /// definite beyond rounding (the smallest eigenvalue above 64 n eps times the largest).
  bool a_is_zero() const { return a_zero_; }
  bool a_is_positive_definite() const { return a_definite_; }
  bool b_is_positive_definite() const { return b_definite_; }

  /// The model for data with n columns in A and d in B: standard deviations per side completed to
  /// std^2 I, every size checked. Throws std::invalid_argument naming the option, or io::DataError
  /// naming the rest file, when a size differs from n or d. Cost O(n^2 + d^2).
  NoiseModel resolved(Eigen::Index n, Eigen::Index d) const;

  /// The model of data whose columns were multiplied by `scale_a` (n factors) and `scale_b` (d
  /// factors), as FitOptions::scale_a and scale_b multiply data given in other units: the
  /// covariances D_a Sigma_A D_a and D_b Sigma_B D_b, the standard deviations and the rest rows'
  /// means scaled alike; source, rest rows, file names and warnings kept. A model resolved to n and
  /// d (resolved()); factors finite and > 0 (std::invalid_argument otherwise). Cost O(n^2 + d^2).
  NoiseModel scaled(const Eigen::VectorXd& scale_a, const Eigen::VectorXd& scale_b) const;

 private:
  friend struct detail::NoiseModelJson;  // the JSON rendering (render/noise_model_json.cpp) reads and restores it
  friend struct detail::LogRestRows;     // from_rest of a log's rest_rows (rest_covariance.cpp)
  NoiseModel() = default;
  // The model of the rest rows' moments (rest_covariance.cpp), with its warnings.
  static NoiseModel from_rest_moments(const detail::RowMoments& a, const detail::RowMoments& b,
                                      std::string a_path, std::string b_path, bool log_rows = false);
  void classify();

  NoiseSource source_ = NoiseSource::Std;
  Eigen::MatrixXd cov_a_, cov_b_;
  Eigen::VectorXd std_a_, std_b_;
  std::optional<std::uint64_t> rest_rows_;
  Eigen::VectorXd rest_mean_a_, rest_mean_b_;
  std::string rest_a_path_, rest_b_path_;
  bool log_rows_ = false;  // Rest from rows of the fitted log (rest_rows), not rest_a and rest_b
  std::vector<Warning> warnings_;
  bool a_zero_ = true, a_definite_ = false, b_definite_ = false;
};

}  // namespace spdfit
