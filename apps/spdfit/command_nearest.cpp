// spdfit nearest [--min-eig E | --corr [--weights W] [--alpha A] [--max-iter N] [--tol T]] [--json] [--output FILE] X
#include <memory>

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
  double min_eig = 0.0;
  bool json = false;
  bool corr = false;
  std::string weights;
  NearestCorrelationOptions correlation;
};

// The weights file: n numbers as one column or one row, checked by the library's rule
// (NearestCorrelationOptions::is_valid) with the file named.
Eigen::VectorXd read_weights(const std::string& path, const NearestCorrelationOptions& options, Eigen::Index n) {
  const Eigen::MatrixXd W = load_matrix(path);
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

// nearest --corr: the nearest correlation matrix.
void run_correlation(const NearestOptionsCli& options, const GlobalOptions& global, const Eigen::MatrixXd& X) {
  NearestCorrelationOptions o = options.correlation;
  if (!options.weights.empty()) o.weights = read_weights(options.weights, o, X.rows());
  const NearestCorrelationResult result = nearest_correlation(X, o);
  for (const std::string& w : result.warnings) warn(global, w);
  if (!options.json) {
    emit(matrix_csv(result.X), options.output);
    return;
  }
  nlohmann::json out;
  out["n"] = X.rows();
  out["corr"] = true;
  out["alpha"] = o.alpha;
  out["X"] = matrix_json(result.X);
  out["distance"] = number_json(result.distance);
  out["iterations"] = result.iterations;
  out["gradient_norm"] = number_json(result.gradient_norm);
  out["converged"] = result.converged;
  out["clipped"] = result.clipped;
  out["cholesky"] = result.cholesky_ok;
  out["warnings"] = result.warnings;
  emit(out.dump(2) + "\n", options.output);
}
}  // namespace

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NearestOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "nearest", "Nearest symmetric positive (semi)definite matrix to X (Higham); repairs covariances");
  CLI::Option* min_eig =
      sub->add_option("--min-eig", options->min_eig,
                      "Smallest eigenvalue allowed (default 0: semidefinite; > 0: strictly definite)")
          ->check(non_negative());
  CLI::Option* corr = sub->add_flag(
      "--corr", options->corr,
      "The nearest correlation matrix (positive semidefinite, unit diagonal; Qi-Sun Newton method)");
  corr->excludes(min_eig);
  sub->add_option("--weights", options->weights,
                  "--corr: file of n positive diagonal weights w; minimizes ||W^1/2 (X - C) W^1/2||_F, W = diag(w)")
      ->needs(corr);
  sub->add_option("--alpha", options->correlation.alpha,
                  "--corr: a floor that keeps the unit diagonal: X = (1 - alpha) X~ + alpha I, eigenvalues >= alpha")
      ->check(number_validator([](double v) { return v >= 0.0 && v < 1.0; }, "number in [0, 1)", "NUMBER in [0, 1)"))
      ->needs(corr);
  sub->add_option("--max-iter", options->correlation.max_iterations, "--corr: Newton iterations at most (default 200)")
      ->check(CLI::Range(1, 100000))
      ->needs(corr);
  sub->add_option("--tol", options->correlation.tolerance,
                  "--corr: stop when ||diag(X) - 1||_2 <= tol sqrt(n) (default 1e-10)")
      ->check(positive())
      ->needs(corr);
  sub->add_flag("--json", options->json, "Print the result and its diagnostics as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  sub->add_option("X", options->path, "File of X (n x n): delimited text or .npy")->required();

  auto run = [options, &global]() {
    const Eigen::MatrixXd X = load_matrix(options->path);
    if (X.rows() != X.cols()) {
      throw io::DataError(options->path, 0, 0,
                          "X is " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) +
                              ": a square matrix is needed");
    }
    if (options->corr) {
      run_correlation(*options, global, X);
      return;
    }
    const NearestSpdResult result = nearest_spd(X, options->min_eig);
    if (result.clipped > 0) {
      warn(global, std::to_string(result.clipped) + " eigenvalue(s) of the symmetric part were below " +
                       io::format_double(options->min_eig) + " and were raised to it");
    }
    if (!options->json) {
      emit(matrix_csv(result.X), options->output);
      return;
    }
    nlohmann::json out;
    out["n"] = X.rows();
    out["min_eig"] = options->min_eig;
    out["X"] = matrix_json(result.X);
    out["distance"] = number_json(result.distance);
    out["clipped"] = result.clipped;
    out["min_eigenvalue_before"] = number_json(result.min_eigenvalue_before);
    emit(out.dump(2) + "\n", options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
