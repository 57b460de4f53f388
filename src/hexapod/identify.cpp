#include "spdfit/hexapod/identify.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "spdfit/compare.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/model.hpp"
#include "factor/basic_reduction.hpp"
#include "numerics/parallel.hpp"
#include "pipeline/log_rows.hpp"
#include "pipeline/offsets.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit::hexapod {

namespace {

// The modes of a replicate's estimate, when it is positive definite.
std::optional<Eigen::VectorXd> replicate_modes(const Eigen::MatrixXd& X, const Eigen::MatrixXd& stiffness) {
  if (X.size() == 0 || X != X.transpose()) return std::nullopt;
  try {
    Eigen::VectorXd modes = modal_frequencies_hz(X, stiffness);
    if (modes.allFinite()) return modes;
  } catch (const std::invalid_argument&) {
    // not positive definite: no modes
  }
  return std::nullopt;
}

// Every estimator on each of N resamples (one factor and reduction per resample, shared). A robust
// estimator's own bootstrap (`robust`: every resample refitted robustly, attached by
// refit_robustly) is in `robust`, by method index: only its modes are derived here.
void bootstrap(std::vector<MethodIdentification>& methods, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
               const IdentifyOptions& options, const Reduction& data,
               const std::vector<std::vector<detail::Replicate>>& robust) {
  const FitOptions& fit_options = options.fit;
  const auto replicates = static_cast<std::size_t>(fit_options.bootstrap);
  std::vector<std::vector<detail::Replicate>> per_method(methods.size(), std::vector<detail::Replicate>(replicates));
  // The plain estimators' resamples (a robust estimator's are its own, below).
  FitOptions plain = detail::options_after_tare(fit_options);
  plain.robust = RobustLoss::None;
  plain.robust_tuning.reset();
  const FitOptions quiet = detail::replicate_options(plain);
  const bool intercept = detail::data_of(data).centred;
  detail::parallel_for(replicates, fit_options.threads, [&](std::size_t r) {
    const TriangularFactor factor = detail::resample_rows(A, B, fit_options.seed, r, intercept);
    std::vector<FitResult> results;
    std::string failure;
    try {
      results = fit_all(reduce(factor, quiet));
    } catch (const std::invalid_argument& e) {
      failure = e.what();  // a resample with fewer rows than columns
    }
    for (std::size_t k = 0; k < methods.size(); ++k) {
      per_method[k][r] = k < results.size() ? detail::replicate_of(std::move(results[k])) : detail::Replicate{{}, failure};
    }
  });
  for (std::size_t k = 0; k < methods.size(); ++k) {
    MethodIdentification& m = methods[k];
    if (!m.result.ok()) continue;
    if (k < robust.size() && m.result.robust) {
      per_method[k] = robust[k];
    } else {
      detail::attach_bootstrap(m.result, per_method[k], fit_options, data);
    }
    if (options.stiffness && m.modes_hz) {
      std::vector<std::optional<Eigen::VectorXd>> modes(replicates);
      for (std::size_t r = 0; r < replicates; ++r) modes[r] = replicate_modes(per_method[k][r].X, *options.stiffness);
      m.modes_uncertainty = detail::summarize_spectrum(*m.modes_hz, modes, fit_options.confidence);
    }
  }
}

}  // namespace

std::vector<MethodIdentification> identify(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                           const IdentifyOptions& options) {
  const Eigen::Index n = A.cols();
  auto check_square = [n](const std::optional<Eigen::MatrixXd>& M, const char* what) {
    if (M && (M->rows() != n || M->cols() != n)) {
      throw std::invalid_argument(std::string("identify: the ") + what + " must be " + std::to_string(n) +
                                  "x" + std::to_string(n) + " like the data's columns, not " +
                                  std::to_string(M->rows()) + "x" + std::to_string(M->cols()));
    }
  };
  check_square(options.truth, "true matrix");
  check_square(options.stiffness, "stiffness matrix");
  if (options.stiffness && !options.stiffness->isApprox(options.stiffness->transpose())) {
    throw std::invalid_argument("identify: the stiffness matrix must be symmetric");
  }

  std::vector<MethodIdentification> out;
  // Offsets (FitOptions::offsets): rest, the rest rows' means subtracted first; estimate, the
  // factor of [1 A B] (the data centred), c reported per estimator.
  std::optional<detail::TaredData> tared;
  if (options.fit.offsets == Offsets::Rest) tared = detail::tared_data(A, B, options.fit);
  const Eigen::MatrixXd& Ad = tared ? tared->A : A;
  const Eigen::MatrixXd& Bd = tared ? tared->B : B;
  const TriangularFactor factor = TriangularFactor::from_data(Ad, Bd, options.fit.offsets == Offsets::Estimate);
  // The estimators on the rows as given (with `robust`, refitted below on reweighted rows).
  FitOptions plain = detail::options_after_tare(options.fit);
  plain.robust = RobustLoss::None;
  plain.robust_tuning.reset();
  const Reduction data = reduce(factor, plain);
  std::vector<FitResult> results = fit_all(data);
  std::vector<std::vector<detail::Replicate>> robust_replicates;
  if (options.fit.robust != RobustLoss::None) {
    // Robust: every estimator that weighs rows refitted on reweighted rows (its own iterations);
    // spde, which has none, as it is. With `bootstrap`, each resample refitted robustly too.
    detail::refit_robustly(Ad, Bd, detail::options_after_tare(options.fit), results, {}, &robust_replicates);
  }
  for (FitResult& result : results) {
    MethodIdentification m;
    m.result = std::move(result);
    FitResult& r = m.result;
    // (A robust fit's offsets are its weighted rows', set by refit_robustly.)
    if (!r.robust || tared) r.offsets = detail::offsets_of(r, factor, options.fit, tared ? &tared->tare : nullptr);
    if (r.ok()) {
      if (options.truth) m.error_vs_truth = error_vs_truth(r, *options.truth);
      if (r.diagnostics.symmetric) {
        m.eigenvalues =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(r.X, Eigen::EigenvaluesOnly).eigenvalues();
      }
      if (options.stiffness && r.diagnostics.positive_definite) {
        try {
          m.modes_hz = modal_frequencies_hz(r.X, *options.stiffness);
        } catch (const std::invalid_argument&) {
          // Positive definite by its eigenvalues but not by Cholesky: so nearly singular
          // that its modes mean nothing. Leave them out.
        }
      }
    }
    out.push_back(std::move(m));
  }
  if (options.fit.bootstrap > 0) bootstrap(out, Ad, Bd, options, data, robust_replicates);
  return out;
}

}  // namespace spdfit::hexapod
