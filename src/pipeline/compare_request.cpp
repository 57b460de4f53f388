// `compare` as one workflow: its option table, its rules and its run.
#include <string>
#include <utility>

#include "pipeline/log_rows.hpp"
#include "spdfit/compare.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"
#include "interface/matrix_inputs.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/sentinels.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<CompareRequest>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec a;
  a.name = "a";
  a.cli = "A";
  a.python = "A";
  a.type = OptionType::Matrix;
  a.help = "File of A (m x n): delimited text or .npy";
  a.positional = true;
  a.required = true;
  a.set = [](CompareRequest& r, const OptionValue& v) { r.a = std::get<MatrixInput>(v); };
  table.push_back(a);
  Spec b;
  b.name = "b";
  b.cli = "B";
  b.python = "B";
  b.type = OptionType::Matrix;
  b.help = "File of B (m x n; m x d for ls and tls, X n x d): delimited text or .npy. Without it, `a_cols` and "
           "`b_cols` choose A's and B's columns in A's file";
  b.positional = true;
  b.set = [](CompareRequest& r, const OptionValue& v) { r.b = std::get<MatrixInput>(v); };
  table.push_back(b);
  Spec truth;
  truth.name = "truth";
  truth.cli = "--truth";
  truth.python = "truth";
  truth.type = OptionType::Matrix;
  truth.value_name = "FILE";
  truth.help = "File of the true X, to report each method's error";
  truth.set = [](CompareRequest& r, const OptionValue& v) { r.truth = std::get<MatrixInput>(v); };
  table.push_back(truth);
  // The fit options that every method shares: the noise (its ratio, or a noise model), and A's and
  // B's columns in one file.
  std::vector<std::string_view> shared = noise_option_names();
  shared.insert(shared.end(), {"a_cols", "b_cols", "scale_a", "scale_b", "rows", "time_col", "offsets", "robust",
                               "robust_tuning"});
  for (Spec& spec : lifted_options(fit_option_table(), &CompareRequest::fit, shared)) table.push_back(std::move(spec));
  for (Spec& spec : output_options(&CompareRequest::output, {"json", "output"}, {"Print every result as JSON"})) {
    table.push_back(std::move(spec));
  }
  return trimmed_rules(std::move(table));
}

}  // namespace

const std::vector<OptionSpec<CompareRequest>>& compare_option_table() {
  static const std::vector<OptionSpec<CompareRequest>> table = make_table();
  return table;
}

void check_compare_request(const CompareRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(compare_option_table(), given);
  spdfit::detail::check_b_given(request.b.given(), request.fit.a_cols, request.fit.b_cols);
}

CompareRun run_compare(const CompareRequest& request) {
  CompareRun out;
  Eigen::MatrixXd A, B;
  if (request.a.from_file()) {
    const std::string b_path = request.b.from_file() ? request.b.path : std::string();
    DataPair data = read_pair(request.a.path, b_path, data_read_options(request.fit, b_path));
    A = std::move(data.A);
    B = std::move(data.B);
    out.warnings = std::move(data.warnings);
  } else {
    A = request.a.values;
    B = request.b.values;
  }
  // One log: the rows fitted and the rest segment (a noise model) from the data themselves.
  FitOptions options = request.fit.resolved_options(A.cols(), B.cols());
  detail::RowNumbers numbers;
  const std::vector<Warning> found =
      detail::apply_log_rows(request.fit, A, B, request.a.from_file() ? request.a.path : "A", options, &numbers);
  out.warnings.insert(out.warnings.end(), found.begin(), found.end());
  std::optional<Eigen::MatrixXd> truth;
  if (request.truth) {
    if (request.truth->from_file()) {
      io::Table table = io::read_table(request.truth->path, request.fit.read);
      out.warnings.insert(out.warnings.end(), table.warnings.begin(), table.warnings.end());
      truth = std::move(table.values);
    } else {
      truth = request.truth->values;
    }
    if (truth->rows() != A.cols() || truth->cols() != B.cols()) {
      const std::string problem = "the true X must be " + std::to_string(A.cols()) + "x" + std::to_string(B.cols());
      if (request.truth->from_file()) throw io::DataError(request.truth->path, 0, 0, problem, Code::DataShape);
      throw InputError(problem, Code::DataShape, "truth");
    }
  }
  if (std::optional<Warning> w = detail::sentinel_warning(A, B, numbers, options.robust != RobustLoss::None)) {
    out.warnings.push_back(std::move(*w));
  }
  // Offsets a fit without them would take for signal: said once for every estimator.
  for (Warning& w : detail::offset_warnings_as_given(A, B, options)) out.warnings.push_back(std::move(w));
  // Rows that dominate the fit: said once, as auto's fit finds them (least squares' for a non-square X).
  const Method judge = A.cols() == B.cols() ? Method::Auto : Method::LeastSquares;
  if (std::optional<Warning> w = detail::dominant_rows_check(A, B, judge, options, numbers)) {
    out.warnings.push_back(std::move(*w));
  }
  out.comparison = compare(A, B, options, truth);
  for (FitResult& r : out.comparison.results) {  // robust fits' rows numbered as in the file
    if (r.robust) detail::number_rows(*r.robust, numbers);
  }
  for (const FitResult& r : out.comparison.results) {
    for (const Warning& w : r.warnings) {
      out.warnings.emplace_back(w.code, std::string(to_string(r.method)) + ": " + w.text, w.subject);
    }
  }
  return out;
}

}  // namespace spdfit
