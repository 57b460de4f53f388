#include "uncertainty/bootstrap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "estimators/auto_settle.hpp"
#include "estimators/diagnostics.hpp"
#include "factor/reduce.hpp"
#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"
#include "estimators/psd_ls_kernel.hpp"
#include "factor/basic_reduction.hpp"
#include "numerics/linalg.hpp"
#include "numerics/parallel.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/format.hpp"
#include "spdfit/random.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

std::vector<std::uint32_t> resample_counts(Index m, std::uint64_t seed, std::size_t replicate) {
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(m), 0);
  Random random(trial_seed(seed, replicate));
  const double rows = static_cast<double>(m);
  for (Index draw = 0; draw < m; ++draw) {
    const auto row = std::min(static_cast<Index>(random.uniform() * rows), m - 1);
    ++counts[static_cast<std::size_t>(row)];
  }
  return counts;
}

Eigen::VectorXd resample_weights(Index m, std::uint64_t seed, std::size_t replicate) {
  const std::vector<std::uint32_t> counts = resample_counts(m, seed, replicate);
  Eigen::VectorXd weights(m);
  for (Index i = 0; i < m; ++i) weights(i) = counts[static_cast<std::size_t>(i)];
  return weights;
}

TriangularFactor resample_rows(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                               std::uint64_t seed, std::size_t replicate, bool intercept) {
  TriangularFactor factor(A.cols(), B.cols(), intercept);
  factor.append(A, B, resample_counts(A.rows(), seed, replicate));
  return factor;
}

std::uint32_t poisson_count(std::uint64_t seed, std::size_t replicate, std::uint64_t group) {
  // One uniform from the key (seed, replicate, group), then inversion of the Poisson(1)
  // distribution function: P(k) = e^-1 / k!.
  const std::uint64_t bits = trial_seed(trial_seed(seed, replicate), group);
  const double u = static_cast<double>(bits >> 11) * 0x1.0p-53;
  double p = 0.36787944117144233;  // e^-1
  double cdf = p;
  std::uint32_t k = 0;
  while (u >= cdf && k < 64) {
    ++k;
    p /= k;
    cdf += p;
  }
  return k;
}

FitOptions replicate_options(const FitOptions& options) {
  FitOptions quiet = options;
  quiet.diagnostics = false;
  quiet.bootstrap = 0;
  return quiet;
}

Replicate replicate_of(FitResult&& fitted) {
  Replicate out;
  if (fitted.ok() && fitted.X.allFinite()) {
    out.X = std::move(fitted.X);
  } else {
    out.message = fitted.ok() ? "the estimate is not finite" : std::move(fitted.message);
  }
  return out;
}

namespace {
// Whether auto's estimate of the full data is its psd-ls fallback at the boundary, which replicates
// then follow (with a noise model auto keeps spd-tls's constrained estimate there, and replicates
// run spd-tls).
bool at_boundary(const FitResult& full) {
  return full.method == Method::PsdLeastSquares && full.diagnostics.reason && full.diagnostics.reason->code == "boundary";
}
}  // namespace

FitResult fit_replicate(const Reduction& data, const FitResult& full) {
  // spde, when auto chose it with a noise model, ran without the model: so do its replicates.
  if (full.method == Method::Spde && data_of(data).options.noise) return fit(without_noise(data), Method::Spde);
  if (!at_boundary(full)) return fit(data, full.method);
  const DynamicReduction& reduced = data_of(data);
  return psd_least_squares_scaled(reduced, auto_floor(reduced));
}

Replicate refit(const TriangularFactor& factor, const FitOptions& options, const FitResult& full) {
  try {
    const Method needs = at_boundary(full) ? Method::PsdLeastSquares : full.method;
    return replicate_of(fit_replicate(reduce_for(factor, replicate_options(options), needs), full));
  } catch (const std::invalid_argument& e) {
    return Replicate{{}, e.what()};  // a resample with fewer rows than columns
  }
}

namespace {

// The q-quantile of sorted values, interpolating linearly between order statistics
// (numpy.quantile's default, Hyndman & Fan's definition 7).
double quantile(const std::vector<double>& sorted, double q) {
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

struct Moments {
  double mean = 0.0, standard_error = 0.0, lower = 0.0, upper = 0.0;
};

// Mean, standard deviation (divisor N - 1; experiment::summarize) and the central `level`
// interval of the values; NaN for all of them with fewer than two values.
Moments moments(std::vector<double> values, double level) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (values.size() < 2) return {nan, nan, nan, nan};
  const experiment::Summary summary = experiment::summarize(values);
  std::sort(values.begin(), values.end());
  return {summary.mean, summary.std, quantile(values, 0.5 * (1.0 - level)), quantile(values, 0.5 * (1.0 + level))};
}

std::string percent(double fraction) { return format_percent(fraction); }

// The standard normal quantile z with Phi(z) = p, p in (0, 1): Newton's method on
// Phi(z) = erfc(-z / sqrt 2) / 2 from the logistic approximation, to rounding (a handful of steps).
double normal_quantile(double p) {
  double z = std::log(p / (1.0 - p)) / 1.702;  // the logistic distribution matched to the normal
  for (int it = 0; it < 50; ++it) {
    const double cdf = 0.5 * std::erfc(-z / std::sqrt(2.0));
    const double density = std::exp(-0.5 * z * z) / std::sqrt(2.0 * 3.14159265358979323846);
    if (!(density > 0.0)) break;
    const double step = (cdf - p) / density;
    z -= step;
    if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(z))) break;
  }
  return z;
}

}  // namespace

SpectrumUncertainty summarize_spectrum(const VectorXd& estimate, const std::vector<std::optional<VectorXd>>& replicates,
                                       double level) {
  SpectrumUncertainty out;
  const Index n = estimate.size();
  out.estimate = estimate;
  out.standard_errors.resize(n);
  out.lower.resize(n);
  out.upper.resize(n);
  std::vector<const VectorXd*> present;
  for (const auto& values : replicates) {
    if (values && values->size() == n && values->allFinite()) {
      present.push_back(&*values);
    } else {
      ++out.failed;
    }
  }
  std::vector<double> column(present.size());
  for (Index i = 0; i < n; ++i) {
    for (std::size_t r = 0; r < present.size(); ++r) column[r] = (*present[r])(i);
    const Moments mo = moments(column, level);
    out.standard_errors(i) = mo.standard_error;
    out.lower(i) = mo.lower;
    out.upper(i) = mo.upper;
  }
  // Clusters: neighbours closer than the sum of their standard errors.
  for (Index i = 0; i < n; ++i) {
    const bool joins = i > 0 && estimate(i) - estimate(i - 1) < out.standard_errors(i) + out.standard_errors(i - 1);
    if (!joins) out.clusters.emplace_back();
    out.clusters.back().push_back(i);
  }
  for (const std::vector<Index>& cluster : out.clusters) {
    if (cluster.size() < 2 || present.size() < 2) continue;
    std::vector<double> smallest(present.size()), largest(present.size());
    for (std::size_t r = 0; r < present.size(); ++r) {
      smallest[r] = (*present[r])(cluster.front());
      largest[r] = (*present[r])(cluster.back());
    }
    const double lower = moments(smallest, level).lower;
    const double upper = moments(largest, level).upper;
    for (Index i : cluster) {
      out.lower(i) = lower;
      out.upper(i) = upper;
    }
  }
  return out;
}

namespace {

// Noise in A biases the least-squares-type estimators and spde towards zero by a margin that does
// not shrink with m, so an interval around them can miss the truth: said where auto's rule, with
// the same data and noise model, would choose the consistent spd-tls instead. Not for a method
// that auto chose (its reason says why), and not for ls, procrustes and psd-ls with a noise model,
// whose notice (ignored_noise_warning) already gives the bias's size and the intervals' risk.
std::optional<Warning> bias_warning(const FitResult& result, const DynamicReduction& data) {
  const Method m = result.method;
  const bool b_only = !models_noise_in_a(m);
  if ((!b_only && m != Method::Spde) || result.diagnostics.reason) return std::nullopt;
  const std::string consistent = data.square() ? "spd-tls (or auto) is" : "tls (for a non-square X) is";
  const std::string name(to_string(m));
  if (const std::optional<ScaledNoise> noise = scaled_noise(data)) {
    if (b_only) return std::nullopt;
    const AutoChoice choice = auto_noise_choice(data, *noise);
    if (std::string(choice.code) != "many_samples") return std::nullopt;
    return Warning(Code::Bias, name + " is biased by the noise in A that " + data.options.noise->option_a() +
                                   " gives, at m = " + std::to_string(data.m) +
                                   " rows (signal-to-noise ratio " + format_number(choice.snr) +
                                   " in A's weakest direction): the bootstrap interval, centred on the biased "
                                   "estimate, can miss the truth; " + consistent + " consistent here");
  }
  const AutoChoice choice = auto_choice(data, data_noise_variance(data));
  if (std::string(choice.code) != "many_samples") return std::nullopt;
  return Warning(Code::Bias, "if A carries noise (the noise estimate cannot tell A's from B's), " + name +
                                 " is biased by it at m = " + std::to_string(data.m) + " rows (signal-to-noise ratio " +
                                 format_number(choice.snr) +
                                 " in A's weakest direction), and the bootstrap interval, centred on the biased "
                                 "estimate, can miss the truth; " + consistent + " consistent here");
}

// Whether an ascending spectrum is singular above `floor` (kSingularRelative): its smallest
// eigenvalue at `floor` to rounding, as the constrained estimators' boundary estimates have it; an
// indefinite X (an unconstrained method's) is not on the boundary.
bool singular(const VectorXd& w, double floor) {
  return w.size() > 0 && std::abs(w(0) - floor) <= kSingularRelative * std::abs(w(w.size() - 1));
}

// BootstrapInterval::Auto resolved: basic when X is singular (psd-ls: X - min_eig I; its
// certificate's smallest eigenvalue) or at least kBoundaryReplicateFraction of the replicates are.
// There the constraint cuts the replicates' distribution at the boundary, so the percentile
// interval repeats the estimate's bias towards it instead of correcting it (bench/results/
// boundary-coverage-intervals-epyc-2026-12-02.md). Percentile elsewhere, and for X not symmetric.
BootstrapInterval auto_interval(const FitResult& result, const VectorXd& estimate,
                                const std::vector<std::optional<VectorXd>>& spectra,
                                const FitOptions& options) {
  if (estimate.size() == 0) return BootstrapInterval::Percentile;
  const bool own_floor = result.method == Method::PsdLeastSquares && !result.diagnostics.reason;
  const double floor = own_floor ? options.min_eig : 0.0;
  bool on_boundary = result.diagnostics.boundary_certificate.has_value() || singular(estimate, floor);
  if (const std::optional<PsdCertificate>& certificate = result.diagnostics.certificate) {
    const double largest = std::abs(estimate(estimate.size() - 1));
    on_boundary = on_boundary || std::abs(certificate->primal_min_eig) <= kSingularRelative * largest;
  }
  if (on_boundary) return BootstrapInterval::Basic;
  std::size_t with = 0, singular_ones = 0;
  for (const std::optional<VectorXd>& w : spectra) {
    if (!w) continue;
    ++with;
    singular_ones += singular(*w, floor) ? 1 : 0;
  }
  const bool many = with > 0 && static_cast<double>(singular_ones) >=
                                    kBoundaryReplicateFraction * static_cast<double>(with);
  return many ? BootstrapInterval::Basic : BootstrapInterval::Percentile;
}

}  // namespace

void attach_bootstrap(FitResult& result, const std::vector<Replicate>& replicates, const FitOptions& options,
                      const Reduction& full_data) {
  Bootstrap boot;
  boot.replicates = static_cast<int>(replicates.size());
  boot.seed = options.seed;
  boot.method = result.method;
  boot.interval.level = options.confidence;
  const double z = normal_quantile(0.5 * (1.0 + options.confidence));
  const Index rows = result.X.rows(), cols = result.X.cols();
  std::vector<const MatrixXd*> present;
  const std::string* first_failure = nullptr;
  for (const Replicate& r : replicates) {
    if (r.X.rows() == rows && r.X.cols() == cols) {
      present.push_back(&r.X);
    } else {
      ++boot.failed;
      if (!first_failure) first_failure = &r.message;
    }
  }
  boot.standard_errors.resize(rows, cols);
  boot.bias.resize(rows, cols);
  boot.interval.lower.resize(rows, cols);
  boot.interval.upper.resize(rows, cols);
  // The spectra of X and of the replicates, for the eigenvalues' intervals and auto's interval.
  const bool symmetric = result.diagnostics.symmetric || (rows == cols && result.X == result.X.transpose());
  std::vector<std::optional<VectorXd>> spectra(replicates.size());
  VectorXd estimate_spectrum;
  if (symmetric) {
    parallel_for(replicates.size(), options.threads, [&](std::size_t r) {
      const MatrixXd& X = replicates[r].X;
      VectorXd w;
      if (X.rows() == rows && X.cols() == cols && X == X.transpose() && symmetric_eigen(X, w)) spectra[r] = w;
    });
    if (!symmetric_eigen(result.X, estimate_spectrum)) {
      throw std::runtime_error("bootstrap: the eigensolver did not converge");
    }
  }
  boot.interval.type = options.interval == BootstrapInterval::Auto
                           ? auto_interval(result, estimate_spectrum, spectra, options)
                           : options.interval;
  std::vector<double> values(present.size());
  for (Index j = 0; j < cols; ++j) {
    for (Index i = 0; i < rows; ++i) {
      for (std::size_t r = 0; r < present.size(); ++r) values[r] = (*present[r])(i, j);
      const Moments mo = moments(values, options.confidence);
      boot.standard_errors(i, j) = mo.standard_error;
      boot.bias(i, j) = mo.mean - result.X(i, j);
      const double estimate = result.X(i, j);
      switch (boot.interval.type) {
        case BootstrapInterval::Percentile:
        case BootstrapInterval::Auto:  // resolved above
          boot.interval.lower(i, j) = mo.lower;
          boot.interval.upper(i, j) = mo.upper;
          break;
        case BootstrapInterval::Basic:  // the percentile interval reflected about the estimate
          boot.interval.lower(i, j) = 2.0 * estimate - mo.upper;
          boot.interval.upper(i, j) = 2.0 * estimate - mo.lower;
          break;
        case BootstrapInterval::Normal:  // centred on the bias-corrected estimate X - bias = 2 X - mean
          boot.interval.lower(i, j) = (2.0 * estimate - mo.mean) - z * mo.standard_error;
          boot.interval.upper(i, j) = (2.0 * estimate - mo.mean) + z * mo.standard_error;
          break;
      }
    }
  }
  if (symmetric) boot.eigenvalues = summarize_spectrum(estimate_spectrum, spectra, options.confidence);

  // Replicates that agree to rounding (a Poisson bootstrap of one group: each replicate is the
  // estimate or nothing; data without noise) carry no spread: a standard error of 0, or of
  // rounding noise, would claim a certainty the data do not show.
  const bool one_value =
      present.size() >= 2 && std::all_of(present.begin() + 1, present.end(), [&](const MatrixXd* X) {
        return (*X - *present.front()).norm() <= kSameReplicateRelative * present.front()->norm();
      });
  if (one_value) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    boot.standard_errors.setConstant(nan);
    boot.bias.setConstant(nan);
    boot.interval.lower.setConstant(nan);
    boot.interval.upper.setConstant(nan);
    boot.eigenvalues.reset();
    result.warnings.push_back(Warning(Code::BootstrapNotice, "the bootstrap has no standard errors: its " + std::to_string(present.size()) +
                              " replicates with an estimate all agree to rounding (at least two different ones are "
                              "needed)"));
  } else if (present.size() < 2) {
    result.warnings.push_back(Warning(Code::BootstrapNotice, "the bootstrap has no standard errors: " + std::to_string(boot.failed) + " of " +
                              std::to_string(boot.replicates) + " replicates had no estimate" +
                              (first_failure ? " (" + *first_failure + ")" : std::string())));
  } else if (boot.failed > 0 && boot.failed * 100 > boot.replicates) {
    result.warnings.push_back(Warning(Code::BootstrapNotice, 
        std::to_string(boot.failed) + " of " + std::to_string(boot.replicates) + " bootstrap replicates (" +
        percent(static_cast<double>(boot.failed) / boot.replicates) + ") had no estimate (the first: " +
        *first_failure + ") and were left out: the standard errors and intervals describe the others"));
  }
  if (std::optional<Warning> w = bias_warning(result, data_of(full_data))) result.warnings.push_back(std::move(*w));
  result.bootstrap = std::move(boot);
}

std::string too_few_groups(std::uint64_t rows, const std::string& instead) {
  const auto groups = (rows + static_cast<std::uint64_t>(kBootstrapGroupRows) - 1) /
                      static_cast<std::uint64_t>(kBootstrapGroupRows);
  return "the streaming bootstrap resamples groups of " + std::to_string(kBootstrapGroupRows) +
         " rows and needs about " + std::to_string(kBootstrapMinGroups) + " groups (" +
         std::to_string(kBootstrapMinGroups * kBootstrapGroupRows) + " rows) for its standard errors, but the data "
         "have " + std::to_string(rows) + (rows == 1 ? " row (" : " rows (") + std::to_string(groups) +
         (groups == 1 ? " group)" : " groups)") + ": " + instead;
}

std::vector<Replicate> run_replicates(std::size_t count, const FitOptions& options,
                                      const std::function<Replicate(std::size_t)>& make) {
  std::vector<Replicate> replicates(count);
  std::mutex progress_mutex;
  std::size_t done = 0;
  parallel_for(count, options.threads, [&](std::size_t r) {
    replicates[r] = make(r);
    if (!options.progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex);  // one call at a time
    options.progress(static_cast<double>(++done) / static_cast<double>(count));
  });
  return replicates;
}

void bootstrap_in_memory(FitResult& result, const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                         const Reduction& full_data) {
  const FitOptions& options = full_data.options();
  const std::vector<Replicate> replicates =
      run_replicates(static_cast<std::size_t>(options.bootstrap), options,
                     [&](std::size_t r) {
                       return refit(resample_rows(A, B, options.seed, r, data_of(full_data).centred), options, result);
                     });
  attach_bootstrap(result, replicates, options, full_data);
  // Each replicate refactors all m rows (O(m n^2) each); from the rows the streaming bootstrap
  // needs on, its one pass over groups of rows is the cheaper way.
  const auto enough_for_groups = static_cast<Index>(kBootstrapMinGroups * kBootstrapGroupRows);
  if (A.rows() >= enough_for_groups) {
    result.warnings.push_back(Warning(Code::BootstrapNotice, "the bootstrap refactored all " + std::to_string(A.rows()) + " rows for each of its " +
                              std::to_string(options.bootstrap) +
                              " replicates; with `stream` it resamples groups of rows in the one pass over the "
                              "files, which is much faster at this size"));
  }
}

}  // namespace spdfit::detail
