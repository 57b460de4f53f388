// spdfit solve [--json] [--threshold T] [--output FILE] A b
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "validators.hpp"
#include "spdfit/io.hpp"
#include "spdfit/linear_system.hpp"

namespace spdfit::cli {

namespace {

struct SolveOptionsCli {
  std::string a_path, b_path, output;
  double threshold = -1.0;
  bool json = false;
};

std::string g(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string vector_text(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + g(v(i));
  return out + "]";
}

// Basis vectors (the columns of B) as a JSON list of vectors.
nlohmann::json basis_json(const Eigen::MatrixXd& B) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index j = 0; j < B.cols(); ++j) out.push_back(vector_json(B.col(j)));
  return out;
}

nlohmann::json solve_json(const LinearSystemResult& r) {
  nlohmann::json out;
  out["consistent"] = r.consistent;
  out["rank"] = r.rank;
  out["nullity"] = r.nullity;
  out["finite_solution_dimension"] = r.finite_solution_dimension;
  out["at_infinity_dimension"] = r.at_infinity_dimension;
  out["condition_number"] = number_json(r.condition_number);
  // One right-hand side: x as a flat list; several: X (n x p) as rows, as `fit` prints X.
  out["solution"] = r.p == 1 ? vector_json(r.solution.col(0)) : matrix_json(r.solution);
  out["residual_norm"] = number_json(r.residual_norm);
  out["null_space"] = basis_json(r.null_space);
  out["range"] = basis_json(r.range);
  out["m"] = r.m;
  out["n"] = r.n;
  out["shape"] = to_string(r.shape);
  out["singular_values"] = vector_json(r.singular_values);
  out["threshold"] = r.threshold;
  out["reciprocal_condition_number"] = number_json(r.reciprocal_condition_number);
  out["effective_condition_number"] = number_json(r.effective_condition_number);
  out["scaled_singular_values"] = vector_json(r.scaled_singular_values);
  out["scaled_condition_number"] = number_json(r.scaled_condition_number);
  out["rank_decided_on"] = "column-scaled";
  out["refinement_steps"] = r.refinement_steps;
  nlohmann::json columns = nlohmann::json::array();
  for (Eigen::Index j = 0; j < r.p; ++j) {
    const ColumnClassification& c = r.columns[j];
    columns.push_back({{"consistent", c.consistent},
                       {"finite_solution_dimension", c.finite_solution_dimension},
                       {"at_infinity_dimension", c.at_infinity_dimension},
                       {"augmented_rank", c.augmented_rank},
                       {"solution", vector_json(r.solution.col(j))},
                       {"residual_norm", number_json(c.residual_norm)},
                       {"backward_error", number_json(c.backward_error)}});
  }
  out["columns"] = columns;
  out["explanation"] = r.explanation;
  out["warnings"] = r.warnings;
  return out;
}

std::string solve_text(const LinearSystemResult& r) {
  std::ostringstream out;
  out << r.explanation << "\n\n";
  out << "rank " << r.rank << ", nullity " << r.nullity << ", condition number " << g(r.condition_number)
      << " (reciprocal " << g(r.reciprocal_condition_number) << ")\n";
  out << "singular values: " << vector_text(r.singular_values) << "\n";
  out << "with unit-norm columns: " << vector_text(r.scaled_singular_values) << ", condition number "
      << g(r.scaled_condition_number) << " (the rank's cut-off: " << g(r.threshold) << " * sigma_max)\n";
  out << "finite solutions: dimension " << r.finite_solution_dimension << "; at infinity: dimension "
      << r.at_infinity_dimension << " (-1: none)\n";
  for (Eigen::Index j = 0; j < r.p; ++j) {
    out << (r.columns[j].consistent ? "solution" : "least-squares solution") << (r.nullity > 0 ? " (minimum norm)" : "");
    if (r.p > 1) out << " for right-hand side " << j + 1;
    out << ": x = " << vector_text(r.solution.col(j)) << ", residual norm " << g(r.columns[j].residual_norm) << "\n";
  }
  out << "null space basis:" << (r.nullity == 0 ? " none" : "") << "\n";
  for (Eigen::Index j = 0; j < r.null_space.cols(); ++j) out << "  " << vector_text(r.null_space.col(j)) << "\n";
  out << "range basis:" << (r.rank == 0 ? " none" : "") << "\n";
  for (Eigen::Index j = 0; j < r.range.cols(); ++j) out << "  " << vector_text(r.range.col(j)) << "\n";
  return out.str();
}

}  // namespace

Command add_solve_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<SolveOptionsCli>();
  CLI::App* sub = app.add_subcommand(
      "solve", "Classify and solve A x = b: rank, consistency, finite solutions and solutions at infinity");
  sub->add_flag("--json", options->json, "Print the classification and solution as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  sub->add_option("--threshold,--rank-tol", options->threshold,
                  "Relative singular-value cut-off: sigma_i <= T * sigma_max counts as zero (default max(m,n)*eps)")
      ->check(rank_tolerance());
  sub->add_option("A", options->a_path, "File of A (m x n): delimited text or .npy")->required();
  sub->add_option("b", options->b_path,
                  "File of b (m x 1, or m x p for p right-hand sides; a single row of m values is read as a column)")
      ->required();

  auto run = [options, &global]() {
    if (options->threshold >= 1.0) throw UsageError("--threshold must be below 1");
    LinearSystemOptions solve_options;
    solve_options.threshold = options->threshold;
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
    emit(options->json ? solve_json(result).dump(2) + "\n" : solve_text(result), options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
