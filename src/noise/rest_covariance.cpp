// NoiseModel from rows recorded at rest: the sample covariances of A's and B's rest rows, in
// memory or streamed from files, and the warnings about a rest segment that is short or moving.
#include <algorithm>
#include <cmath>
#include <utility>
#include <stdexcept>
#include <string>

#include "noise/noise_checks.hpp"
#include "noise/rest_moments.hpp"
#include "pipeline/sentinels.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/row_reader.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace detail {

void RowMoments::add(const Eigen::Ref<const MatrixXd>& block) {
  const Index k = block.rows();
  if (k == 0) return;
  constexpr std::size_t kNamed = 5;
  for (Index i = 0; i < k; ++i) {
    Index column = -1;
    for (Index j = 0; j < block.cols() && column < 0; ++j) {
      if (std::abs(block(i, j)) >= kSentinelMagnitude) column = j;
    }
    if (column < 0) continue;
    ++sentinel_rows_;
    if (sentinels_.size() < kNamed) {
      sentinels_.push_back({rows_ + static_cast<std::uint64_t>(i), column, block(i, column)});
    }
  }
  const VectorXd block_mean = block.colwise().mean().transpose();
  const MatrixXd centered = block.rowwise() - block_mean.transpose();
  MatrixXd block_m2 = MatrixXd::Zero(block.cols(), block.cols());
  block_m2.selfadjointView<Eigen::Lower>().rankUpdate(centered.transpose());
  block_m2.triangularView<Eigen::StrictlyUpper>() = block_m2.transpose();
  if (rows_ == 0) {
    rows_ = static_cast<std::uint64_t>(k);
    mean_ = block_mean;
    m2_ = std::move(block_m2);
    return;
  }
  // Chan, Golub & LeVeque (1979): the merge of two sets' means and centered sums of squares.
  const double na = static_cast<double>(rows_), nb = static_cast<double>(k), total = na + nb;
  const VectorXd delta = block_mean - mean_;
  mean_ += delta * (nb / total);
  m2_ += block_m2;
  m2_.noalias() += (na * nb / total) * delta * delta.transpose();
  rows_ += static_cast<std::uint64_t>(k);
}

MatrixXd RowMoments::covariance() const {
  MatrixXd S = m2_ / (static_cast<double>(rows_) - 1.0);
  return 0.5 * (S + S.transpose());
}

}  // namespace detail

namespace {

// A rest segment this many rows per column or longer gives covariances to trust: the variances'
// relative standard error is sqrt(2 / (N - 1)), 14% at 10 rows per column of 10 columns.
constexpr double kRestRowsPerColumn = 10.0;
// A column of the rest accelerations whose mean is this many of its standard deviations from
// zero looks like motion (or an offset), not noise about zero.
constexpr double kRestMeanDeviations = 3.0;

}  // namespace

NoiseModel NoiseModel::from_rest_moments(const detail::RowMoments& a, const detail::RowMoments& b,
                                         std::string a_path, std::string b_path, bool log_rows) {
  NoiseModel model;
  model.source_ = NoiseSource::Rest;
  model.log_rows_ = log_rows;
  model.cov_a_ = a.covariance();
  model.cov_b_ = b.covariance();
  model.rest_mean_a_ = a.mean();
  model.rest_mean_b_ = b.mean();
  model.rest_rows_ = a.rows();
  model.rest_a_path_ = std::move(a_path);
  model.rest_b_path_ = std::move(b_path);
  model.classify();

  const std::uint64_t rows = a.rows();
  const Index widest = std::max(model.cov_a_.rows(), model.cov_b_.rows());
  const double wanted = kRestRowsPerColumn * static_cast<double>(widest);
  if (static_cast<double>(rows) < wanted) {
    model.warnings_.push_back(Warning(Code::NoiseModelNotice, 
        "the rest segment has " + std::to_string(rows) + " rows, fewer than " + detail::number(kRestRowsPerColumn) +
        " per column (" + detail::number(wanted) + " for " + std::to_string(widest) +
        " columns): its covariances are uncertain (the variances' relative standard error is about " +
        detail::number(100.0 * std::sqrt(2.0 / (static_cast<double>(rows) - 1.0))) +
        "%); record a longer stretch at rest"));
  }
  // A logger's code for an invalid reading among the rest rows: the covariances would be its square.
  const auto sentinels = [&](const detail::RowMoments& side, const std::string& path,
                             const std::string& which) {
    if (side.sentinel_rows() == 0) return;
    std::string named;
    for (const detail::RowMoments::Sentinel& s : side.sentinels()) {
      named += (named.empty() ? "" : ", ") + std::to_string(s.row + 1) + " (" + detail::number(s.value) +
               " in column " + std::to_string(s.column + 1) + ")";
    }
    const bool one = side.sentinel_rows() == 1;
    // Rows of a file are its data rows; rows given in memory (or chosen from a log by rest_rows)
    // are counted among the rest rows.
    std::string text = "the rest rows of " + which + (path.empty() ? std::string() : " (" + path + ")") +
                       " hold a value of magnitude 1e30 or more in " + (path.empty() ? "rest " : "") +
                       (one ? "row " : "rows ") + named;
    if (side.sentinel_rows() > side.sentinels().size()) {
      text += " and " + std::to_string(side.sentinel_rows() - side.sentinels().size()) + " more";
    }
    text += ": a logger's code for an invalid reading, not noise; the noise model's covariances are its "
            "square and decide the fit: leave " +
            std::string(one ? "that row" : "those rows") + " out of the rest rows";
    model.warnings_.push_back(Warning(Code::Outliers, text, "rest_rows"));
  };
  sentinels(a, model.rest_a_path_, "A");
  sentinels(b, model.rest_b_path_, "B");
  std::string moving;
  for (Index j = 0; j < model.rest_mean_a_.size(); ++j) {
    const double sd = std::sqrt(model.cov_a_(j, j));
    const double mean = model.rest_mean_a_(j);
    if (std::abs(mean) > kRestMeanDeviations * sd) {
      moving += (moving.empty() ? "" : ", ") + std::to_string(j + 1) + " (mean " + detail::number(mean) +
                ", standard deviation " + detail::number(sd) + ")";
    }
  }
  if (!moving.empty()) {
    model.warnings_.push_back(Warning(Code::NoiseModelNotice, 
        "the rest rows of A (" + model.option_a() + ") have a mean far from zero for their spread in column(s) " + moving +
        ": at rest the accelerations are zero; was the machine moving, or is there an offset?"));
  }
  return model;
}

namespace {

// The checks of from_rest's rows, naming them `option` ("`rest_a`"; "A's rest segment" for a log's
// rest_rows) with `subject` as the error's subject.
void check_rest_rows(const Eigen::Ref<const MatrixXd>& rows, const std::string& option, const std::string& subject) {
  if (rows.cols() < 1) throw InputError(option + " has no columns", Code::NoiseModel, subject);
  if (rows.rows() < 2) {
    throw InputError(option + " has " + std::to_string(rows.rows()) +
                         " row(s): a covariance needs at least 2 (and about 10 per column to be trusted)",
                     Code::NoiseModel, subject);
  }
  if (!rows.allFinite()) throw InputError(option + " holds NaN or Inf", Code::NoiseModel, subject);
}

}  // namespace

NoiseModel detail::LogRestRows::from_rest(const Eigen::Ref<const MatrixXd>& rest_a,
                                          const Eigen::Ref<const MatrixXd>& rest_b) {
  check_rest_rows(rest_a, "A's rest segment", "rest_rows");
  check_rest_rows(rest_b, "B's rest segment", "rest_rows");
  detail::RowMoments a, b;
  a.add(rest_a);
  b.add(rest_b);
  return NoiseModel::from_rest_moments(a, b, {}, {}, true);
}

NoiseModel NoiseModel::from_rest(const Eigen::Ref<const MatrixXd>& rest_a, const Eigen::Ref<const MatrixXd>& rest_b) {
  check_rest_rows(rest_a, "`rest_a`", "rest_a");
  check_rest_rows(rest_b, "`rest_b`", "rest_b");
  if (rest_a.rows() != rest_b.rows()) {
    throw InputError("`rest_b` has " + std::to_string(rest_b.rows()) + " rows but `rest_a` has " +
                         std::to_string(rest_a.rows()) + ": the rest rows of A and B come from the same stretch of log",
                     Code::NoiseModel, "rest_b");
  }
  detail::RowMoments a, b;
  a.add(rest_a);
  b.add(rest_b);
  return from_rest_moments(a, b, {}, {});
}

NoiseModel NoiseModel::from_rest_files(const std::string& rest_a_path, const std::string& rest_b_path,
                                       const io::ReadOptions& read, Index block_rows) {
  if (block_rows < 1) throw OptionError("`block_rows` must be at least 1", Code::OptionValue, "block_rows");
  io::ReadOptions finite = read;
  finite.allow_nonfinite = false;  // a covariance of NaN is no noise model
  // One log's selections: A's columns of the rest rows of A, B's of those of B.
  const bool split = read.columns.size() == 2;
  auto stream = [&](const std::string& path, const char* option, std::size_t selection) {
    detail::RowMoments moments;
    io::ReadOptions side = finite;
    if (split) side.columns = {read.columns[selection]};
    io::RowReader reader(path, side);
    MatrixXd block;
    while (reader.read(block_rows, &block) > 0) moments.add(block);
    if (moments.rows() < 2) {
      throw io::DataError(path, 0, 0,
                          std::string("the rest rows (") + option + ") are " + std::to_string(moments.rows()) +
                              ": a covariance needs at least 2 (and about 10 per column to be trusted)",
                          Code::NoiseModel);
    }
    return moments;
  };
  const detail::RowMoments a = stream(rest_a_path, "`rest_a`", 0);
  const detail::RowMoments b = stream(rest_b_path, "`rest_b`", 1);
  if (a.rows() != b.rows()) {
    throw io::DataError(rest_b_path, 0, 0,
                        "the rest rows of B (`rest_b`) are " + std::to_string(b.rows()) + " but those of A (" +
                            rest_a_path + ") are " + std::to_string(a.rows()) +
                            ": the rest rows of A and B come from the same stretch of log",
                        Code::NoiseModel);
  }
  return from_rest_moments(a, b, rest_a_path, rest_b_path);
}

}  // namespace spdfit
