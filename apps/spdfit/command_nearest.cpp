// spdfit nearest [--min-eig E | --min-eig-rel R] [--corr | --keep-diag | --via-corr] [--weights W]
//                [--alpha A] [--max-iter N] [--tol T] [--json] [--output FILE] X
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_spd.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {
struct NearestOptionsCli {
  std::string path, output;
  double min_eig = 0.0, min_eig_rel = 0.0;
  bool json = false, corr = false, keep_diag = false, via_corr = false;
  std::string weights;
  NearestCorrelationOptions newton;
};

// The weights file: n numbers as one column or one row, checked by the library's rule
// (NearestCorrelationOptions::is_valid) with the file named.
Eigen::VectorXd read_weights(const std::string& path, const NearestCorrelationOptions& options, Eigen::Index n,
                             const GlobalOptions& global) {
  const Eigen::MatrixXd W = load_matrix(path, global);
  if (W.size() != n || (W.rows() != 1 && W.cols() != 1)) {
    throw io::DataError(path, 0, 0,
                        "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) + ": give " +
                            std::to_string(n) + " numbers (one per row of X) as one column or one row");
  }
  NearestCorrelationOptions weighted = options;
  weighted.weights = Eigen::Map<const Eigen::VectorXd>(W.data(), n);
  std::string error;
  if (!weighted.is_valid(n, &error)) throw io::DataError(path, 0, 0, error);
  return weighted.weights;
}

nlohmann::json result_json(const NearestOptionsCli& options, const NearestResult& result, Eigen::Index n,
                           EigenvalueFloor floor) {
  nlohmann::json out;
  out["n"] = n;
  out["corr"] = options.corr;
  out["keep_diag"] = options.keep_diag;
  out["via_corr"] = options.via_corr;
  out["min_eig"] = number_json(result.min_eig);
  out["min_eig_rel"] = floor.relative ? nlohmann::json(floor.value) : nlohmann::json(nullptr);
  out["alpha"] = options.newton.alpha;
  out["X"] = matrix_json(result.X);
  out["distance"] = number_json(result.distance);
  out["clipped"] = result.clipped;
  out["min_eigenvalue_before"] = number_json(result.min_eigenvalue_before);
  out["iterations"] = result.iterations;
  out["gradient_norm"] = number_json(result.gradient_norm);
  out["converged"] = result.converged;
  out["cholesky"] = result.cholesky_ok;
  out["warnings"] = result.warnings;
  return out;
}
}  // namespace

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NearestOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "nearest",
      "Repair a covariance or correlation matrix: the nearest symmetric positive definite matrix to X (Higham), "
      "or with a fixed diagonal (--corr, --keep-diag, --via-corr)");
  CLI::Option* min_eig =
      sub->add_option("--min-eig", options->min_eig,
                      "Smallest eigenvalue allowed, absolute (0: the plain semidefinite projection)")
          ->check(non_negative());
  CLI::Option* min_eig_rel =
      sub->add_option("--min-eig-rel", options->min_eig_rel,
                      "Smallest eigenvalue allowed, relative: R times the largest eigenvalue of X's symmetric part "
                      "(default 1e-8 when no floor is given: positive definite, Cholesky-factorable)")
          ->check(relative_floor());
  min_eig->excludes(min_eig_rel);
  CLI::Option* corr = sub->add_flag(
      "--corr", options->corr,
      "The nearest correlation matrix (unit diagonal; Qi-Sun Newton method)");
  CLI::Option* keep_diag = sub->add_flag(
      "--keep-diag", options->keep_diag,
      "Keep X's diagonal (trusted variances): the nearest matrix with it (the same Newton method); "
      "with --corr the diagonal is the unit one");
  CLI::Option* via_corr = sub->add_flag(
      "--via-corr", options->via_corr,
      "statsmodels' cov_nearest route: scale X to a correlation, repair it (the floor applies to it), scale back");
  via_corr->excludes(corr)->excludes(keep_diag);
  CLI::Option* weights = sub->add_option(
      "--weights", options->weights,
      "With --corr, --keep-diag or --via-corr: file of n positive diagonal weights w; minimizes "
      "||W^1/2 (X - C) W^1/2||_F, W = diag(w)");
  CLI::Option* alpha =
      sub->add_option("--alpha", options->newton.alpha,
                      "With --corr or --via-corr: NAG g02ab's floor, X = (1 - alpha) X~ + alpha I: the same as "
                      "--min-eig alpha for a unit diagonal")
          ->check(number_validator([](double v) { return v >= 0.0 && v < 1.0; }, "number in [0, 1)",
                                   "NUMBER in [0, 1)"));
  alpha->excludes(min_eig)->excludes(min_eig_rel);
  CLI::Option* max_iter =
      sub->add_option("--max-iter", options->newton.max_iterations,
                      "With --corr, --keep-diag or --via-corr: Newton iterations at most (default 200)")
          ->check(CLI::Range(1, 100000));
  CLI::Option* tol = sub->add_option("--tol", options->newton.tolerance,
                                     "With --corr, --keep-diag or --via-corr: stop when ||diag(X) - d||_2 <= "
                                     "tol sqrt(n) max(d) (default 1e-10)")
                         ->check(positive());
  sub->add_flag("--json", options->json, "Print the result and its diagnostics as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout (X.npy: X as a NumPy file)");
  sub->add_option("X", options->path, "File of X (n x n): delimited text or .npy")->required();

  auto run = [options, &global, min_eig, min_eig_rel, alpha, weights, max_iter, tol]() {
    const bool newton = options->corr || options->keep_diag || options->via_corr;
    if (options->json) check_text_output(options->output, "--json");
    if (alpha->count() > 0 && !options->corr && !options->via_corr) {
      throw UsageError("--alpha is the unit diagonal's floor: it needs --corr or --via-corr (otherwise give "
                       "--min-eig)");
    }
    if (!newton) {
      for (const CLI::Option* o : {weights, max_iter, tol}) {
        if (o->count() > 0) throw UsageError(o->get_name() + " needs --corr, --keep-diag or --via-corr");
      }
    }
    const Eigen::MatrixXd X = load_matrix(options->path, global);
    if (X.rows() != X.cols()) {
      throw io::DataError(options->path, 0, 0,
                          "X is " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) +
                              ": a square matrix is needed");
    }
    // The floor: --min-eig, --min-eig-rel, --alpha, or by default the relative 1e-8.
    const auto given = [](const CLI::Option* o, double value) {
      return o->count() > 0 ? std::optional<double>(value) : std::nullopt;
    };
    const EigenvalueFloor floor = EigenvalueFloor::chosen(
        given(min_eig, options->min_eig), given(min_eig_rel, options->min_eig_rel), alpha->count() > 0);
    NearestResult result;
    try {
      if (newton) {
        NearestCorrelationOptions o = options->newton;
        o.floor = floor;
        if (!options->weights.empty()) o.weights = read_weights(options->weights, o, X.rows(), global);
        result = options->corr       ? nearest_correlation(X, o)
                 : options->keep_diag ? nearest_keep_diagonal(X, o)
                                      : nearest_via_correlation(X, o);
      } else {
        result = nearest_spd(X, floor);
      }
    } catch (const std::invalid_argument& e) {
      throw io::DataError(options->path, 0, 0, e.what());
    }
    if (!newton && result.clipped > 0) {
      // The clip's note, as the command has always printed it (the library leaves it to `clipped`).
      result.warnings.push_back(std::to_string(result.clipped) + " eigenvalue(s) of the symmetric part were below " +
                                trimmed(result.min_eig) +
                                (floor.relative ? " (" + trimmed(floor.value) + " x the largest eigenvalue)" : "") +
                                " and were raised to it");
    }
    for (const std::string& w : result.warnings) warn(global, w);
    if (!options->json) {
      emit_matrix(result.X, options->output);
      return;
    }
    emit(result_json(*options, result, X.rows(), floor).dump(2) + "\n", options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
