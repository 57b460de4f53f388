// spdfit solve [--json] [--threshold T] [--output FILE] A b
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "validators.hpp"
#include "spdfit/io.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/render.hpp"

namespace spdfit::cli {

namespace {

struct SolveOptionsCli {
  std::string a_path, b_path, output;
  double threshold = -1.0;
  bool json = false;
};

}  // namespace

Command add_solve_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<SolveOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "solve", "Classify and solve A x = b: rank, consistency, finite solutions and solutions at infinity");
  sub->add_flag("--json", options->json, "Print the classification and solution as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  sub->add_option("--threshold,--rank-tol", options->threshold,
                  "Relative singular-value cut-off, applied to A with its columns scaled to unit norm (not to A's "
                  "raw singular values): sigma_i <= T * sigma_max of the scaled A counts as zero (default "
                  "max(m,n)*eps)")
      ->check(rank_tolerance());
  sub->add_option("A", options->a_path, "File of A (m x n): delimited text or .npy")->required();
  sub->add_option("b", options->b_path,
                  "File of b (m x 1, or m x p for p right-hand sides; a single row of m values is read as a column)")
      ->required();

  auto run = [options, &global]() {
    if (options->threshold >= 1.0) throw UsageError("--threshold must be below 1");
    LinearSystemOptions solve_options;
    if (options->threshold >= 0.0) solve_options.rank_tolerance = options->threshold;
    const Eigen::MatrixXd A = load_matrix(options->a_path, global);
    if (A.cols() > solve_options.max_unknowns) {
      throw io::DataError(options->a_path, 0, 0,
                          "A has " + std::to_string(A.cols()) + " columns: solve supports at most " +
                              std::to_string(solve_options.max_unknowns) + " unknowns");
    }
    Eigen::MatrixXd b = load_matrix(options->b_path, global);
    if (b.rows() != A.rows() && b.rows() == 1 && b.cols() == A.rows()) b.transposeInPlace();
    if (b.rows() != A.rows()) {
      throw io::DataError(options->b_path, 0, 0,
                          "b has " + std::to_string(b.rows()) + " rows but A (" + options->a_path + ") has " +
                              std::to_string(A.rows()) + ": one entry of b per equation is needed");
    }
    const LinearSystemResult result = solve(A, b, solve_options);
    for (const std::string& w : result.warnings) warn(global, w);
    if (!result.ok()) throw DataFailure(result.message);
    emit(options->json ? to_json(result) : report(result), options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
