// NoiseModel from standard deviations and covariance matrices: validation, and completing a model
// to the data's sizes. The rest rows' factories are in rest_covariance.cpp.
#include "spdfit/noise_model.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "noise/noise_checks.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// A covariance read from a file or computed elsewhere may differ from its transpose by rounding:
// up to this fraction of its largest entry is symmetric (its symmetric part is kept).
constexpr double kSymmetryTolerance = 1e-10;
// An eigensolver's rounding: eigenvalues within kDefiniteMargin n eps lambda_max of zero are zero
// to working precision (the margin auto uses for "positive definite beyond rounding").
constexpr double kDefiniteMargin = 64.0;

std::string size_text(const MatrixXd& M) { return std::to_string(M.rows()) + "x" + std::to_string(M.cols()); }

}  // namespace

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

CovarianceClass classify_covariance(const MatrixXd& S) {
  CovarianceClass out;
  if (S.size() == 0) return out;
  out.zero = (S.array() == 0.0).all();
  if (out.zero) return out;
  const VectorXd w = Eigen::SelfAdjointEigenSolver<MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
  out.min_eigenvalue = w(0);
  out.max_eigenvalue = w(w.size() - 1);
  const double margin = kDefiniteMargin * static_cast<double>(S.rows()) * kEps * std::abs(out.max_eigenvalue);
  out.positive_definite = out.min_eigenvalue > margin;
  out.semidefinite = out.min_eigenvalue >= -margin;
  return out;
}

MatrixXd checked_covariance(const MatrixXd& S, const std::string& option) {
  if (S.size() == 0) throw InputError(option + " is empty: give a covariance matrix", Code::NoiseModel, bare(option));
  if (S.rows() != S.cols()) {
    throw InputError(option + " is " + size_text(S) + ": a covariance matrix is square", Code::NoiseModel, bare(option));
  }
  for (Index j = 0; j < S.cols(); ++j)
    for (Index i = 0; i < S.rows(); ++i)
      if (!std::isfinite(S(i, j))) {
        throw InputError(option + " entry (" + std::to_string(i + 1) + ", " + std::to_string(j + 1) +
                                    ") is " + number(S(i, j)) + ": a covariance is finite", Code::NoiseModel, bare(option));
      }
  const double biggest = S.cwiseAbs().maxCoeff();
  for (Index j = 0; j < S.cols(); ++j)
    for (Index i = 0; i < j; ++i)
      if (std::abs(S(i, j) - S(j, i)) > kSymmetryTolerance * biggest) {
        throw InputError(option + " is not symmetric: entry (" + std::to_string(i + 1) + ", " +
                                    std::to_string(j + 1) + ") is " + number(S(i, j)) + " but entry (" +
                                    std::to_string(j + 1) + ", " + std::to_string(i + 1) + ") is " +
                                    number(S(j, i)), Code::NoiseModel, bare(option));
      }
  MatrixXd symmetric = 0.5 * (S + S.transpose());
  const CovarianceClass c = classify_covariance(symmetric);
  if (!c.zero && !c.semidefinite) {
    throw InputError(option + " is not positive semidefinite: its smallest eigenvalue is " +
                                number(c.min_eigenvalue) + " (the largest " + number(c.max_eigenvalue) +
                                "), and a covariance has no negative eigenvalues", Code::NoiseModel, bare(option));
  }
  return symmetric;
}

}  // namespace detail

namespace {

VectorXd checked_std(const VectorXd& s, const std::string& option) {
  if (s.size() == 0) {
    throw OptionError(option + " is empty: give one standard deviation for every column, or one for all",
                      Code::OptionValue, detail::bare(option));
  }
  for (Index i = 0; i < s.size(); ++i) {
    if (!(s(i) >= 0.0) || !std::isfinite(s(i))) {
      throw OptionError(option + (s.size() > 1 ? " value " + std::to_string(i + 1) : std::string()) + " is " +
                            detail::number(s(i)) + ": a standard deviation is a finite number >= 0 (0: exact)",
                        Code::OptionValue, detail::bare(option));
    }
  }
  return s;
}

// diag(std^2) for `columns` columns, from one value for all or one for each.
MatrixXd covariance_of_std(const VectorXd& s, Index columns, const char* side, const std::string& option) {
  if (s.size() != 1 && s.size() != columns) {
    throw OptionError(option + " has " + std::to_string(s.size()) + " values but " + side + " has " +
                          std::to_string(columns) + " columns: give one for every column, or one for all",
                      Code::OptionValue, detail::bare(option));
  }
  const VectorXd variances = s.size() == 1 ? VectorXd::Constant(columns, s(0) * s(0)) : VectorXd(s.cwiseAbs2());
  return variances.asDiagonal();
}

}  // namespace

NoiseModel NoiseModel::from_std(const VectorXd& std_a, const VectorXd& std_b) {
  NoiseModel model;
  model.source_ = NoiseSource::Std;
  model.std_a_ = checked_std(std_a, "`noise_std_a`");
  model.std_b_ = checked_std(std_b, "`noise_std_b`");
  // Per column, the size is known: the covariances now. Per side, when the data's sizes are.
  if (model.std_a_.size() > 1) model.cov_a_ = covariance_of_std(model.std_a_, model.std_a_.size(), "A", "");
  if (model.std_b_.size() > 1) model.cov_b_ = covariance_of_std(model.std_b_, model.std_b_.size(), "B", "");
  model.classify();
  return model;
}

NoiseModel NoiseModel::from_std(double std_a, double std_b) {
  return from_std(VectorXd::Constant(1, std_a), VectorXd::Constant(1, std_b));
}

NoiseModel NoiseModel::from_cov(const MatrixXd& cov_a, const MatrixXd& cov_b) {
  NoiseModel model;
  model.source_ = NoiseSource::Cov;
  model.cov_a_ = detail::checked_covariance(cov_a, "`noise_cov_a`");
  model.cov_b_ = detail::checked_covariance(cov_b, "`noise_cov_b`");
  model.classify();
  return model;
}

void NoiseModel::classify() {
  // A side given by one standard deviation (not yet resolved) is decided by that value.
  auto decide = [](const MatrixXd& cov, const VectorXd& std_dev, bool& zero, bool* definite) {
    if (cov.size() > 0) {
      const detail::CovarianceClass c = detail::classify_covariance(cov);
      zero = c.zero;
      if (definite) *definite = c.positive_definite;
    } else {
      zero = std_dev.size() > 0 && (std_dev.array() == 0.0).all();
      if (definite) *definite = std_dev.size() > 0 && (std_dev.array() > 0.0).all();
    }
  };
  decide(cov_a_, std_a_, a_zero_, &a_definite_);
  bool b_zero = false;
  decide(cov_b_, std_b_, b_zero, &b_definite_);
}

std::string NoiseModel::option_a() const {
  switch (source_) {
    case NoiseSource::Std:
      return "`noise_std_a`";
    case NoiseSource::Cov:
      return "`noise_cov_a`";
    case NoiseSource::Rest:
      return log_rows_ ? "`rest_rows`" : "`rest_a`";
  }
  return "`noise`";
}

std::string NoiseModel::option_b() const {
  switch (source_) {
    case NoiseSource::Std:
      return "`noise_std_b`";
    case NoiseSource::Cov:
      return "`noise_cov_b`";
    case NoiseSource::Rest:
      return log_rows_ ? "`rest_rows`" : "`rest_b`";
  }
  return "`noise`";
}

NoiseModel NoiseModel::resolved(Index n, Index d) const {
  NoiseModel out = *this;
  if (source_ == NoiseSource::Std) {
    out.cov_a_ = covariance_of_std(std_a_, n, "A", option_a());
    out.cov_b_ = covariance_of_std(std_b_, d, "B", option_b());
    out.classify();
    return out;
  }
  auto check = [&](const MatrixXd& cov, Index columns, const char* side, const std::string& option,
                   const std::string& path) {
    if (cov.rows() == columns) return;
    if (source_ == NoiseSource::Rest) {
      const std::string problem = "the rest rows of " + std::string(side) + " (" + option + ") have " +
                                  std::to_string(cov.rows()) + " columns but " + side + " has " +
                                  std::to_string(columns) + ": they must come from the same sensors";
      if (!path.empty()) throw io::DataError(path, 0, 0, problem, Code::NoiseModel);
      throw InputError(problem, Code::NoiseModel, detail::bare(option));
    }
    throw InputError(option + " is " + detail::size_text(cov) + " but " + side + " has " +
                         std::to_string(columns) + " columns: it must be " + std::to_string(columns) + "x" +
                         std::to_string(columns),
                     Code::NoiseModel, detail::bare(option));
  };
  check(cov_a_, n, "A", option_a(), rest_a_path_);
  check(cov_b_, d, "B", option_b(), rest_b_path_);
  return out;
}

NoiseModel NoiseModel::scaled(const Eigen::VectorXd& scale_a, const Eigen::VectorXd& scale_b) const {
  if (cov_a_.rows() != scale_a.size() || cov_b_.rows() != scale_b.size()) {
    throw std::invalid_argument("NoiseModel::scaled: a model resolved to the factors' sizes is needed");
  }
  const auto valid = [](const Eigen::VectorXd& f) { return f.allFinite() && (f.array() > 0.0).all(); };
  if (!valid(scale_a) || !valid(scale_b)) {
    throw std::invalid_argument("NoiseModel::scaled: the factors must be finite numbers > 0");
  }
  NoiseModel out = *this;
  out.cov_a_ = scale_a.asDiagonal() * cov_a_ * scale_a.asDiagonal();
  out.cov_b_ = scale_b.asDiagonal() * cov_b_ * scale_b.asDiagonal();
  // A side given by one standard deviation for every column has one per column once scaled.
  const auto scale_std = [](const VectorXd& std_dev, const VectorXd& f) -> VectorXd {
    if (std_dev.size() == 0) return std_dev;
    return std_dev.size() == f.size() ? VectorXd(std_dev.cwiseProduct(f)) : VectorXd(std_dev(0) * f);
  };
  out.std_a_ = scale_std(std_a_, scale_a);
  out.std_b_ = scale_std(std_b_, scale_b);
  if (rest_mean_a_.size() == scale_a.size()) out.rest_mean_a_ = rest_mean_a_.cwiseProduct(scale_a);
  if (rest_mean_b_.size() == scale_b.size()) out.rest_mean_b_ = rest_mean_b_.cwiseProduct(scale_b);
  out.classify();
  return out;
}

}  // namespace spdfit
