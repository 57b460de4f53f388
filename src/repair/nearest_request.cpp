// The repairs' option table: each option declared once, with everything the front ends need.
#include "spdfit/nearest_request.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "spdfit/labels.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<NearestRequest>;

double real(const OptionValue& v) { return std::get<double>(v); }

// The options that need a Newton repair, and their message's list.
const std::vector<std::string_view> kNewtonFlags = {"corr", "keep_diag", "via_corr"};

Spec flag(std::string_view name, std::string_view cli, std::string_view python, std::string_view help,
          void (*set)(NearestRequest&, const OptionValue&), std::optional<OptionValue> (*get)(const NearestRequest&)) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = python;
  spec.type = OptionType::Flag;
  spec.nullable = false;
  spec.help = help;
  spec.set = set;
  spec.get = get;
  return spec;
}

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  table.push_back(flag(
      "corr", "--corr", "", "The nearest correlation matrix (unit diagonal; Qi-Sun Newton method)",
      [](NearestRequest& r, const OptionValue& v) { r.corr = std::get<bool>(v); },
      [](const NearestRequest& r) -> std::optional<OptionValue> { return r.corr; }));
  table.push_back(flag(
      "keep_diag", "--keep-diag", "keep_diag",
      "Keep X's diagonal (trusted variances): the nearest matrix with it (the same Newton method); with `corr` "
      "the diagonal is the unit one",
      [](NearestRequest& r, const OptionValue& v) { r.keep_diag = std::get<bool>(v); },
      [](const NearestRequest& r) -> std::optional<OptionValue> { return r.keep_diag; }));
  Spec via = flag(
      "via_corr", "--via-corr", "via_corr",
      "statsmodels' cov_nearest route: scale X to a correlation, repair it (the floor applies to it), scale back",
      [](NearestRequest& r, const OptionValue& v) { r.via_corr = std::get<bool>(v); },
      [](const NearestRequest& r) -> std::optional<OptionValue> { return r.via_corr; });
  via.excludes = {"corr", "keep_diag"};
  table.push_back(via);

  Spec min_eig;
  min_eig.name = "min_eig";
  min_eig.cli = "--min-eig";
  min_eig.python = "min_eig";
  min_eig.type = OptionType::Real;
  min_eig.value_name = "NUMBER";
  min_eig.help = "Smallest eigenvalue allowed, absolute (0: the plain semidefinite projection)";
  min_eig.range = {0.0, std::numeric_limits<double>::infinity()};
  min_eig.excludes = {"min_eig_rel"};
  min_eig.set = [](NearestRequest& r, const OptionValue& v) { r.min_eig = real(v); };
  min_eig.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.min_eig) return std::nullopt;
    return *r.min_eig;
  };
  table.push_back(min_eig);

  Spec relative;
  relative.name = "min_eig_rel";
  relative.cli = "--min-eig-rel";
  relative.python = "min_eig_rel";
  relative.type = OptionType::Real;
  relative.value_name = "NUMBER";
  relative.help = "Smallest eigenvalue allowed, relative: R times the largest eigenvalue of X's symmetric part; "
                  "with `keep_diag` or `via_corr`, of its correlation matrix D^-1/2 X D^-1/2 (D = diag(X)), a floor "
                  "below every variance whatever their units (1e-8 when no floor is given: positive definite, "
                  "Cholesky-factorable)";
  relative.default_text = "1e-8";
  relative.range = {0.0, 1.0, false, true};
  relative.set = [](NearestRequest& r, const OptionValue& v) { r.min_eig_rel = real(v); };
  relative.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.min_eig_rel) return std::nullopt;
    return *r.min_eig_rel;
  };
  table.push_back(relative);

  Spec alpha;
  alpha.name = "alpha";
  alpha.cli = "--alpha";
  alpha.python = "alpha";
  alpha.type = OptionType::Real;
  alpha.value_name = "NUMBER";
  alpha.help = "With `corr` or `via_corr`: NAG g02ab's floor, X = (1 - alpha) X~ + alpha I: the same as "
               "`min_eig` alpha for a unit diagonal";
  alpha.range = {0.0, 1.0, false, true};
  alpha.needs = {"corr", "via_corr"};
  alpha.needs_message = "`alpha` is the unit diagonal's floor: it needs `corr` or `via_corr` (otherwise give `min_eig`)";
  alpha.excludes = {"min_eig", "min_eig_rel"};
  alpha.set = [](NearestRequest& r, const OptionValue& v) { r.alpha = real(v); };
  alpha.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.alpha) return std::nullopt;
    return *r.alpha;
  };
  table.push_back(alpha);

  Spec weights;
  weights.name = "weights";
  weights.cli = "--weights";
  weights.python = "weights";
  weights.type = OptionType::Matrix;
  weights.value_name = "FILE";
  weights.help = "With `corr`, `keep_diag` or `via_corr`: n positive diagonal weights w; minimizes "
                 "||W^1/2 (X - C) W^1/2||_F, W = diag(w)";
  weights.needs = kNewtonFlags;
  weights.set = [](NearestRequest& r, const OptionValue& v) { r.weights = std::get<MatrixInput>(v); };
  table.push_back(weights);

  Spec iterations;
  iterations.name = "max_iterations";
  iterations.cli = "--max-iter";
  iterations.python = "max_iter";
  iterations.type = OptionType::Integer;
  iterations.value_name = "N";
  iterations.help = "With `corr`, `keep_diag` or `via_corr`: Newton iterations at most";
  iterations.default_text = "200";
  iterations.range = {1.0, 1e5};
  iterations.needs = kNewtonFlags;
  iterations.set = [](NearestRequest& r, const OptionValue& v) { r.max_iterations = int(std::get<std::int64_t>(v)); };
  iterations.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.max_iterations};
  };
  table.push_back(iterations);

  Spec tolerance;
  tolerance.name = "tolerance";
  tolerance.cli = "--tol";
  tolerance.python = "tol";
  tolerance.type = OptionType::Real;
  tolerance.value_name = "NUMBER";
  tolerance.help = "With `corr`, `keep_diag` or `via_corr`: stop when ||diag(X) - d||_2 <= tol sqrt(n) max(d)";
  tolerance.default_text = "1e-10";
  tolerance.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  tolerance.needs = kNewtonFlags;
  tolerance.set = [](NearestRequest& r, const OptionValue& v) { r.tolerance = real(v); };
  tolerance.get = [](const NearestRequest& r) -> std::optional<OptionValue> { return r.tolerance; };
  table.push_back(tolerance);
  return table;
}

}  // namespace

EigenvalueFloor NearestRequest::floor() const { return EigenvalueFloor::chosen(min_eig, min_eig_rel, alpha.has_value()); }

NearestCorrelationOptions NearestRequest::correlation_options() const {
  NearestCorrelationOptions options;
  options.floor = floor();
  if (weights.from_file()) throw std::invalid_argument("the weights' file is read by run_nearest: give their values");
  const Eigen::MatrixXd& w = weights.values;
  if (w.size() > 0 && w.rows() != 1 && w.cols() != 1) {
    throw InputError("the weights are " + std::to_string(w.rows()) + "x" + std::to_string(w.cols()) +
                         ": give one per row of X, as one column or one row",
                     Code::DataShape, "weights");
  }
  if (w.size() > 0) options.weights = Eigen::Map<const Eigen::VectorXd>(w.data(), w.size());
  options.alpha = alpha.value_or(options.alpha);
  options.max_iterations = max_iterations;
  options.tolerance = tolerance;
  return options;
}

const std::vector<OptionSpec<NearestRequest>>& nearest_option_table() {
  static const std::vector<OptionSpec<NearestRequest>> table = make_table();
  return table;
}

void check_nearest_request(const std::vector<std::string_view>& given,
                           const std::vector<std::string_view>& unavailable) {
  check_option_combination(nearest_option_table(), given, unavailable);
}

NearestResult nearest(const Eigen::Ref<const Eigen::MatrixXd>& C, const NearestRequest& request) {
  if (!request.newton()) return nearest_spd(C, request.floor());
  const NearestCorrelationOptions options = request.correlation_options();
  return request.corr        ? nearest_correlation(C, options)
         : request.keep_diag ? nearest_keep_diagonal(C, options)
                             : nearest_via_correlation(C, options);
}

namespace {

using CommandSpec = OptionSpec<NearestCommand>;

std::vector<CommandSpec> make_command_table() {
  std::vector<CommandSpec> table;
  CommandSpec x;
  x.name = "x";
  x.cli = "X";
  x.type = OptionType::Matrix;
  x.help = "File of X (n x n): delimited text or .npy";
  x.positional = true;
  x.required = true;
  x.set = [](NearestCommand& c, const OptionValue& v) { c.matrix = std::get<MatrixInput>(v); };
  table.push_back(x);
  for (CommandSpec& spec : lifted_options(nearest_option_table(), &NearestCommand::repair)) table.push_back(std::move(spec));
  for (CommandSpec& spec : output_options(
           &NearestCommand::output, {"json", "header", "output"},
           {"Print the result and its diagnostics as JSON (with the variables' names, when X's file has them)",
            "Print X as CSV with a header row and row labels: the names of X's file (its header row, else its "
            "index column; numbers where it has none), as pandas' read_csv(..., index_col=0) reads them",
            "Write to FILE instead of stdout (X.npy: X as a NumPy file)"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

// One row too many in text, the first of consecutive integers (0, 1, ..., 7 or 1, 2, ..., 8): a
// header of numbers read as data.
bool counts_up(const Eigen::MatrixXd& X) {
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    if (X(0, j) != X(0, 0) + static_cast<double>(j) || X(0, j) != std::floor(X(0, j))) return false;
  }
  return true;
}

}  // namespace

const std::vector<OptionSpec<NearestCommand>>& nearest_command_table() {
  static const std::vector<OptionSpec<NearestCommand>> table = make_command_table();
  return table;
}

NearestRun run_nearest(const NearestCommand& command) {
  NearestRun run;
  run.repair = command.repair;
  Eigen::MatrixXd X;
  const std::string& path = command.matrix.path;
  if (command.matrix.from_file()) {
    // With the labels of an index column: the names of X's variables (df.cov().to_csv()).
    io::LabelledTable labelled = io::read_labelled_table(path, command.read);
    std::vector<Warning> name_warnings;
    run.names = variable_names(labelled, path, &name_warnings);
    io::Table& file = labelled.table;
    run.warnings = std::move(file.warnings);
    X = std::move(file.values);
    if (X.rows() != X.cols()) {
      std::string problem =
          "X is " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) + ": a square matrix is needed";
      if (X.rows() == X.cols() + 1 && X.cols() >= 3 && file.first_data_line > 0 && counts_up(X)) {
        problem += "; line " + std::to_string(file.first_data_line) +
                   ", its first row, looks like a header of column names" +
                   (command.read.header_row == io::HeaderRow::Absent
                        ? " (read as data because of --no-header)"
                        : ": delete it or give names that are not numbers");
      }
      throw io::DataError(path, 0, 0, problem, Code::DataShape);
    }
    run.warnings.insert(run.warnings.end(), name_warnings.begin(), name_warnings.end());
  } else {
    X = command.matrix.values;
  }
  if (command.repair.weights.from_file()) {
    const Eigen::MatrixXd W = io::read_matrix(command.repair.weights.path, command.read);
    const Eigen::Index n = X.rows();
    if (W.size() != n || (W.rows() != 1 && W.cols() != 1)) {
      throw io::DataError(command.repair.weights.path, 0, 0,
                          "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) +
                              ": give " + std::to_string(n) + " numbers (one per row of X) as one column or one row",
                          Code::DataShape);
    }
    NearestCorrelationOptions weighted;
    weighted.weights = Eigen::Map<const Eigen::VectorXd>(W.data(), n);
    std::string error;
    if (!weighted.is_valid(n, &error)) throw io::DataError(command.repair.weights.path, 0, 0, error, Code::DataValue);
    run.repair.weights = MatrixInput{{}, W};
  }
  try {
    run.result = nearest(X, run.repair);
  } catch (const std::invalid_argument& e) {
    const Code code = tier(code_of(e)) == Tier::Data ? code_of(e) : Code::DataValue;
    if (command.matrix.from_file()) throw io::DataError(path, 0, 0, e.what(), code);
    throw;
  }
  run.warnings.insert(run.warnings.end(), run.result.warnings.begin(), run.result.warnings.end());
  return run;
}

}  // namespace spdfit
