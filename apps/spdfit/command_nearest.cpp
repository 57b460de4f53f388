// spdfit nearest [--min-eig E | --min-eig-rel R] [--corr | --keep-diag | --via-corr] [--weights W]
//                [--fixed MASK] [--h-weights H] [--rank K | --factors K [--factors-only]] [--min-diag D]
//                [--alpha A] [--max-iter N] [--tol T] [--json | --header] [--output FILE] X
#include <cmath>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/render.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {
// The options that are the command line's own; the request's come from the library's table
// (nearest_option_table).
struct NearestOptionsCli {
  std::string path, output;
  bool json = false;
  bool header = false;
  std::unique_ptr<TableOptions<NearestRequest>> table;
};

// The weights file: n numbers as one column or one row, checked by the library's rule
// (NearestCorrelationOptions::is_valid) with the file named.
std::vector<double> read_weights(const std::string& path, Eigen::Index n, const GlobalOptions& global) {
  const Eigen::MatrixXd W = load_matrix(path, global);
  if (W.size() != n || (W.rows() != 1 && W.cols() != 1)) {
    throw io::DataError(path, 0, 0,
                        "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) + ": give " +
                            std::to_string(n) + " numbers (one per row of X) as one column or one row");
  }
  NearestCorrelationOptions weighted;
  weighted.weights = Eigen::Map<const Eigen::VectorXd>(W.data(), n);
  std::string error;
  if (!weighted.is_valid(n, &error)) throw io::DataError(path, 0, 0, error);
  return std::vector<double>(W.data(), W.data() + n);
}

// A matrix option's file (`fixed`'s mask or pairs, `h_weights`' H), named by the same variables as
// X when it has names (a labelled matrix as pandas writes one: reordered to X's order), checked by
// the library's rule for an n x n matrix (NearestStructure::is_valid) with the file named.
Eigen::MatrixXd read_structure(const std::string& path, std::string_view name, Eigen::Index n, DiagonalRule rule,
                               const std::vector<std::string>& x_names, const GlobalOptions& global) {
  io::LabelledTable labelled = io::read_labelled_table(path, global.read);
  for (const std::string& w : labelled.table.warnings) warn(global, w);
  std::vector<std::string> name_warnings;
  const std::vector<std::string> names = variable_names(labelled, path, &name_warnings);
  for (const std::string& w : name_warnings) warn(global, w);
  Eigen::MatrixXd M = std::move(labelled.table.values);
  if (M.rows() == n && M.cols() == n) {  // a mask or weights (not a list of pairs)
    std::string error;
    std::optional<Eigen::MatrixXd> aligned = aligned_by_name(M, names, x_names, &error);
    if (!aligned) throw io::DataError(path, 0, 0, error);
    M = std::move(*aligned);
  }
  NearestStructure structure;
  (name == "fixed" ? structure.fixed : structure.h_weights) = M;
  std::string error;
  if (!structure.is_valid(n, rule, &error)) throw io::DataError(path, 0, 0, error);
  return M;
}

// The result's JSON (the library's, with the variables' names) with the options the repair ran with.
std::string result_json(const NearestRequest& options, const NearestResult& result, EigenvalueFloor floor,
                        const std::vector<std::string>& names) {
  return with_fields(to_json(result, names), {{"corr", options.corr},
                                       {"keep_diag", options.keep_diag},
                                       {"via_corr", options.via_corr},
                                       {"min_eig_rel", floor.relative ? nlohmann::json(floor.value) : nlohmann::json(nullptr)},
                                       {"alpha", options.alpha.value_or(0.0)}});
}
}  // namespace

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<NearestOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "nearest",
      "Repair a covariance or correlation matrix: the nearest symmetric positive definite matrix to X (Higham), "
      "or with a fixed diagonal (--corr, --keep-diag, --via-corr), entries kept (--fixed), elementwise weights "
      "(--h-weights), a rank (--rank) or factor structure (--factors)");
  options->table = std::make_unique<TableOptions<NearestRequest>>(*sub, nearest_option_table());
  CLI::Option* json = sub->add_flag(
      "--json", options->json,
      "Print the result and its diagnostics as JSON (with the variables' names, when X's file has them)");
  sub->add_flag("--header", options->header,
                "Print X as CSV with a header row and row labels: the names of X's file (its header row, else its "
                "index column; numbers where it has none), as pandas' read_csv(..., index_col=0) reads them")
      ->excludes(json);
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout (X.npy: X as a NumPy file)");
  sub->add_option("X", options->path, "File of X (n x n): delimited text or .npy")->required();

  auto run = [options, &global]() {
    if (options->json) check_text_output(options->output, "--json");
    if (options->header) check_text_output(options->output, "--header");
    const TableOptions<NearestRequest>& table = *options->table;
    try {
      check_nearest_request(table.given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    // With the labels of an index column: the names of X's variables (df.cov().to_csv()).
    io::LabelledTable labelled = io::read_labelled_table(options->path, global.read);
    std::vector<std::string> name_warnings;
    const std::vector<std::string> names = variable_names(labelled, options->path, &name_warnings);
    io::Table& file = labelled.table;
    for (const std::string& w : file.warnings) warn(global, w);
    const Eigen::MatrixXd X = std::move(file.values);
    if (X.rows() != X.cols()) {
      std::string problem =
          "X is " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) + ": a square matrix is needed";
      // One row too many in text, the first of consecutive integers (0, 1, ..., 7 or 1, 2, ..., 8), is
      // a header of numbers read as data.
      const auto counts_up = [&X] {
        for (Eigen::Index j = 0; j < X.cols(); ++j) {
          if (X(0, j) != X(0, 0) + static_cast<double>(j) || X(0, j) != std::floor(X(0, j))) return false;
        }
        return true;
      };
      if (X.rows() == X.cols() + 1 && X.cols() >= 3 && file.first_data_line > 0 && counts_up()) {
        problem += "; line " + std::to_string(file.first_data_line) +
                   ", its first row, looks like a header of column names" +
                   (global.read.header_row == io::HeaderRow::Absent ? " (read as data because of --no-header)"
                                                                    : ": delete it or give names that are not numbers");
      }
      throw io::DataError(options->path, 0, 0, problem);
    }
    NearestRequest request;
    const DiagonalRule rule = table.was_given("corr")        ? DiagonalRule::Unit
                              : table.was_given("keep_diag") ? DiagonalRule::Kept
                                                             : DiagonalRule::Free;
    table.apply(
        request, [&](const std::string& path) { return read_weights(path, X.rows(), global); },
        [&](const std::string& path, std::string_view name) {
          return read_structure(path, name, X.rows(), rule, names, global);
        });
    const EigenvalueFloor floor = request.floor();
    NearestResult result;
    try {
      result = nearest(X, request);
    } catch (const std::invalid_argument& e) {
      throw io::DataError(options->path, 0, 0, e.what());
    }
    for (const std::string& w : name_warnings) warn(global, w);
    for (const std::string& w : result.warnings) warn(global, w);
    // With `factors_only` the answer is F (n x K): its rows are the variables, its columns the factors.
    const bool loadings = request.factors_only;
    if (options->header) {
      if (loadings) {
        std::vector<std::string> factor_names;
        for (Eigen::Index k = 0; k < result.F.cols(); ++k) factor_names.push_back("factor " + std::to_string(k + 1));
        emit(labelled_csv(result.F, names, factor_names), options->output);
      } else {
        emit(labelled_csv(result.X, names, names), options->output);
      }
      return;
    }
    if (!options->json) {
      emit_matrix(loadings ? result.F : result.X, options->output);
      return;
    }
    emit(result_json(request, result, floor, names), options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
