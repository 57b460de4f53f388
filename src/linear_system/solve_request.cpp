// `solve` as one workflow: its option table and its run.
#include "spdfit/solve_request.hpp"

#include <limits>
#include <string>

namespace spdfit {

namespace {

using Spec = OptionSpec<SolveRequest>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec a;
  a.name = "a";
  a.cli = "A";
  a.type = OptionType::Matrix;
  a.help = "File of A (m x n): delimited text or .npy";
  a.positional = true;
  a.required = true;
  a.set = [](SolveRequest& r, const OptionValue& v) { r.a = std::get<MatrixInput>(v); };
  table.push_back(a);

  Spec b;
  b.name = "b";
  b.cli = "b";
  b.type = OptionType::Matrix;
  b.help = "File of b (m x 1, or m x p for p right-hand sides; a single row of m values is read as a column)";
  b.positional = true;
  b.required = true;
  b.set = [](SolveRequest& r, const OptionValue& v) { r.b = std::get<MatrixInput>(v); };
  table.push_back(b);

  Spec threshold;
  threshold.name = "threshold";
  threshold.cli = "--threshold,--rank-tol";
  threshold.python = "threshold";
  threshold.type = OptionType::Real;
  threshold.value_name = "T";
  threshold.help = "Relative singular-value cut-off, applied to A with its columns scaled to unit norm (not to A's "
                   "raw singular values): sigma_i <= T * sigma_max of the scaled A counts as zero";
  threshold.default_text = "max(m, n) eps";
  threshold.range = {0.0, 1.0, false, true};
  threshold.set = [](SolveRequest& r, const OptionValue& v) { r.options.rank_tolerance = std::get<double>(v); };
  threshold.get = [](const SolveRequest& r) -> std::optional<OptionValue> {
    if (!r.options.rank_tolerance) return std::nullopt;
    return *r.options.rank_tolerance;
  };
  table.push_back(threshold);

  Spec rcond;
  rcond.name = "rcond_warning";
  rcond.type = OptionType::Real;
  rcond.help = "The reciprocal condition number (of the column-scaled A) below which a warning says that A is "
               "ill-conditioned";
  rcond.default_text = "1e-12";
  rcond.range = {0.0, 1.0};
  rcond.set = [](SolveRequest& r, const OptionValue& v) { r.options.rcond_warning = std::get<double>(v); };
  rcond.get = [](const SolveRequest& r) -> std::optional<OptionValue> { return r.options.rcond_warning; };
  table.push_back(rcond);

  for (Spec& spec : output_options(&SolveRequest::output, {"json", "output"},
                                   {"Print the classification and solution as JSON"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

// A matrix given as a file (read with its warnings) or as values.
Eigen::MatrixXd values_of(const MatrixInput& input, const io::ReadOptions& read, std::vector<Warning>& warnings) {
  if (!input.from_file()) return input.values;
  io::Table table = io::read_table(input.path, read);
  warnings.insert(warnings.end(), table.warnings.begin(), table.warnings.end());
  return std::move(table.values);
}

[[noreturn]] void shape_problem(const MatrixInput& input, const char* name, const std::string& problem) {
  if (input.from_file()) throw io::DataError(input.path, 0, 0, problem, Code::DataShape);
  throw InputError(problem, Code::DataShape, name);
}

}  // namespace

const std::vector<OptionSpec<SolveRequest>>& solve_option_table() {
  static const std::vector<OptionSpec<SolveRequest>> table = make_table();
  return table;
}

std::optional<Problem> SolveRun::failure() const {
  if (result.ok()) return std::nullopt;
  return Problem{Code::NumericalFailure, result.message, {}};
}

SolveRun run_solve(const SolveRequest& request) {
  SolveRun out;
  const Eigen::MatrixXd A = values_of(request.a, request.read, out.warnings);
  if (A.cols() > request.options.max_unknowns) {
    shape_problem(request.a, "A",
                  "A has " + std::to_string(A.cols()) + " columns: solve supports at most " +
                      std::to_string(request.options.max_unknowns) + " unknowns");
  }
  Eigen::MatrixXd b = values_of(request.b, request.read, out.warnings);
  if (b.rows() != A.rows() && b.rows() == 1 && b.cols() == A.rows()) b.transposeInPlace();
  if (b.rows() != A.rows()) {
    shape_problem(request.b, "b",
                  "b has " + std::to_string(b.rows()) + " rows but A" +
                      (request.a.from_file() ? " (" + request.a.path + ")" : std::string()) + " has " +
                      std::to_string(A.rows()) + ": one entry of b per equation is needed");
  }
  out.result = solve(A, b, request.options);
  out.warnings.insert(out.warnings.end(), out.result.warnings.begin(), out.result.warnings.end());
  return out;
}

}  // namespace spdfit
