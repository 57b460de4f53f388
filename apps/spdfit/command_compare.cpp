// spdfit compare [--truth T] [--json] A B: every estimator on the same data, side by side.
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "table_options.hpp"
#include "spdfit/compare.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/io.hpp"
#include "spdfit/render.hpp"

namespace spdfit::cli {

namespace {

struct CompareOptionsCli {
  std::string a_path, b_path, truth_path, output;
  bool json = false;
  std::unique_ptr<TableOptions<FitRequest>> table;
};

}  // namespace

Command add_compare_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<CompareOptionsCli>();
  CLI::App* sub = app.add_subcommand("compare", "Run every estimator on A X ~= B and show them side by side");
  sub->add_option("--truth", options->truth_path, "File of the true X, to report each method's error");
  sub->add_flag("--json", options->json, "Print every result as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  // The fit options that every method shares: the noise (its ratio, or a noise model), and A's and
  // B's columns in one file.
  std::vector<std::string_view> here = noise_option_names();
  here.insert(here.end(), {"a_cols", "b_cols"});
  options->table = std::make_unique<TableOptions<FitRequest>>(*sub, fit_option_table(),
                                                              all_but(fit_option_table(), here));
  sub->add_option("A", options->a_path, "File of A (m x n): delimited text or .npy")->required();
  sub->add_option("B", options->b_path,
                  "File of B (m x n; m x d for ls and tls, X n x d): delimited text or .npy. Without it, "
                  "--a-cols and --b-cols choose A's and B's columns in A's file");

  auto run = [options, &global]() {
    FitRequest request;
    request.read = global.read;
    options->table->apply(request);
    const DataPair data = load_pair(options->a_path, options->b_path, request, global);
    std::optional<Eigen::MatrixXd> truth;
    if (!options->truth_path.empty()) {
      truth = load_matrix(options->truth_path, global);
      if (truth->rows() != data.A.cols() || truth->cols() != data.B.cols()) {
        throw io::DataError(options->truth_path, 0, 0, "the true X must be " + std::to_string(data.A.cols()) +
                                                           "x" + std::to_string(data.B.cols()));
      }
    }
    check_fit_options(request, options->table->given());
    const FitOptions fit_options = resolved_fit_options(request, data.A.cols(), data.B.cols());
    const Comparison comparison = compare(data.A, data.B, fit_options, truth);
    for (const FitResult& r : comparison.results) {
      for (const std::string& w : r.warnings) warn(global, std::string(to_string(r.method)) + ": " + w);
    }
    emit(options->json ? to_json(comparison) : report(comparison), options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
