// The repairs' option table: each option declared once, with everything the front ends need.
#include "spdfit/nearest_request.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "factor/data_checks.hpp"
#include "repair/repair.hpp"
#include "spdfit/labels.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<NearestRequest>;

double real(const OptionValue& v) { return std::get<double>(v); }

// The options that need a Newton repair, and their message's list.
const std::vector<std::string_view> kNewtonFlags = {"corr", "keep_diag", "via_corr"};
// The options of an iterative repair: a fixed diagonal, kept entries or elementwise weights.
const std::vector<std::string_view> kIterative = {"corr", "keep_diag", "via_corr", "fixed", "h_weights"};

// A matrix option: the command line's FILE, an array in Python and MATLAB.
Spec matrix(std::string_view name, std::string_view cli, std::string_view help,
            void (*set)(NearestRequest&, const OptionValue&)) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = name;
  spec.type = OptionType::Matrix;
  spec.value_name = "FILE";
  spec.help = help;
  spec.set = set;
  return spec;
}

// A count K of the rank and factor repairs.
Spec count(std::string_view name, std::string_view cli, std::string_view help,
           void (*set)(NearestRequest&, const OptionValue&), std::optional<OptionValue> (*get)(const NearestRequest&)) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.python = name;
  spec.type = OptionType::Integer;
  spec.value_name = "K";
  spec.help = help;
  spec.range = {1.0, 1e9};
  spec.set = set;
  spec.get = get;
  return spec;
}

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
  weights.needs = {"corr", "keep_diag", "via_corr", "fixed"};
  weights.excludes = {"h_weights", "factors"};
  weights.set = [](NearestRequest& r, const OptionValue& v) { r.weights = std::get<MatrixInput>(v); };
  table.push_back(weights);

  Spec fixed = matrix(
      "fixed", "--fixed",
      "Entries of X kept exactly (a trusted block): an n x n mask (1: kept, 0: free; symmetric) or index pairs i, j "
      "as two columns (counted from 1), each keeping (i, j) and (j, i); the diagonal as `corr` or `keep_diag` say "
      "(without them, the mask's diagonal entries are kept too). A kept block that is not positive semidefinite, or "
      "kept entries no such matrix has, are data errors that say which",
      [](NearestRequest& r, const OptionValue& v) { r.fixed = std::get<MatrixInput>(v); });
  fixed.excludes = {"via_corr", "rank", "factors"};
  table.push_back(fixed);

  Spec h_weights = matrix(
      "h_weights", "--h-weights",
      "Elementwise weights H (n x n, symmetric, >= 0; 0: the entry is free, as for a pair never observed "
      "together): minimizes ||H o (X - C)||_F (NAG g02aj), by an augmented Lagrangian method with Newton steps; "
      "reports the dual's lower bound and the KKT residual",
      [](NearestRequest& r, const OptionValue& v) { r.h_weights = std::get<MatrixInput>(v); });
  h_weights.excludes = {"via_corr", "rank", "factors"};
  table.push_back(h_weights);

  Spec rank = count(
      "rank", "--rank",
      "The nearest correlation matrix of rank at most K (NAG g02ak; with `keep_diag`, the covariance with its "
      "variances kept): a non-convex problem, solved by spectral projected gradients from several documented starts "
      "(modified PCA of X and of the convex solution, random points); reports every start, the local optimality "
      "residual and the convex solution's distance, a lower bound. Takes `weights`",
      [](NearestRequest& r, const OptionValue& v) { r.rank = int(std::get<std::int64_t>(v)); },
      [](const NearestRequest& r) -> std::optional<OptionValue> {
        if (r.rank == 0) return std::nullopt;
        return std::int64_t{r.rank};
      });
  rank.needs = {"corr", "keep_diag"};
  rank.needs_message = "`rank` needs `corr` (the nearest correlation matrix of rank <= K) or `keep_diag` (the "
                       "covariance of rank <= K with its variances kept)";
  rank.excludes = {"min_eig", "min_eig_rel", "alpha", "factors"};
  table.push_back(rank);

  Spec factors = count(
      "factors", "--factors",
      "The nearest correlation matrix with K-factor structure X = diag(1 - ||f_i||^2) + F F^T, F n x K "
      "(statsmodels' corr_nearest_factor, NAG g02ae), by spectral projected gradients from products of X with n x K "
      "matrices only: for large n. Returns F as well (`factors_only`: F alone)",
      [](NearestRequest& r, const OptionValue& v) { r.factors = int(std::get<std::int64_t>(v)); },
      [](const NearestRequest& r) -> std::optional<OptionValue> {
        if (r.factors == 0) return std::nullopt;
        return std::int64_t{r.factors};
      });
  factors.needs = {"corr"};
  factors.needs_message = "`factors` is a correlation matrix's structure (unit diagonal): it needs `corr`";
  factors.excludes = {"keep_diag", "min_eig", "min_eig_rel", "alpha"};
  table.push_back(factors);

  Spec only = flag(
      "factors_only", "--factors-only", "factors_only",
      "With `factors`: F only (n x K), X not formed: no n x n matrix besides the input",
      [](NearestRequest& r, const OptionValue& v) { r.factors_only = std::get<bool>(v); },
      [](const NearestRequest& r) -> std::optional<OptionValue> { return r.factors_only; });
  only.needs = {"factors"};
  table.push_back(only);

  Spec min_diag;
  min_diag.name = "min_diag";
  min_diag.cli = "--min-diag";
  min_diag.python = "min_diag";
  min_diag.type = OptionType::Real;
  min_diag.value_name = "D";
  min_diag.help = "Variances (diagonal entries) below D, zero or negative as pairwise deletion leaves them, are "
                  "raised to D before the repair, with a warning naming them; without it, `keep_diag` and `via_corr` "
                  "refuse such a diagonal";
  min_diag.range = {0.0, std::numeric_limits<double>::infinity()};
  min_diag.set = [](NearestRequest& r, const OptionValue& v) { r.min_diag = real(v); };
  min_diag.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.min_diag) return std::nullopt;
    return *r.min_diag;
  };
  table.push_back(min_diag);

  Spec iterations;
  iterations.name = "max_iterations";
  iterations.cli = "--max-iter";
  iterations.python = "max_iter";
  iterations.type = OptionType::Integer;
  iterations.value_name = "N";
  iterations.help = "With `corr`, `keep_diag`, `via_corr`, `fixed` or `h_weights`: Newton iterations at most (`rank`: "
                    "gradient steps from each start; `factors`: gradient steps)";
  iterations.default_text = "200; `rank`, `factors`: 2000";
  iterations.range = {1.0, 1e6};
  iterations.needs = kIterative;
  iterations.set = [](NearestRequest& r, const OptionValue& v) { r.max_iterations = int(std::get<std::int64_t>(v)); };
  iterations.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.max_iterations) return std::nullopt;
    return std::int64_t{*r.max_iterations};
  };
  table.push_back(iterations);

  Spec tolerance;
  tolerance.name = "tolerance";
  tolerance.cli = "--tol";
  tolerance.python = "tol";
  tolerance.type = OptionType::Real;
  tolerance.value_name = "NUMBER";
  tolerance.help = "With `corr`, `keep_diag` or `via_corr`: stop when ||diag(X) - d||_2 <= tol sqrt(n) max(d) (`fixed`: "
                   "the kept entries' residual; `h_weights`: the relative KKT residuals; `rank`, `factors`: the "
                   "relative stationarity residual)";
  tolerance.default_text = "1e-10; `rank`, `factors`: 1e-9";
  tolerance.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  tolerance.needs = kIterative;
  tolerance.set = [](NearestRequest& r, const OptionValue& v) { r.tolerance = real(v); };
  tolerance.get = [](const NearestRequest& r) -> std::optional<OptionValue> {
    if (!r.tolerance) return std::nullopt;
    return *r.tolerance;
  };
  table.push_back(tolerance);
  return table;
}

}  // namespace

EigenvalueFloor NearestRequest::floor() const { return EigenvalueFloor::chosen(min_eig, min_eig_rel, alpha.has_value()); }

namespace {

// A matrix option's values: std::invalid_argument while it is still a file (run_nearest reads it).
const Eigen::MatrixXd& values_of(const MatrixInput& input, const char* option) {
  if (input.from_file()) {
    throw std::invalid_argument(std::string("the file of `") + option + "` is read by run_nearest: give its values");
  }
  return input.values;
}

// The diagonal weights as a vector: InputError unless one row or one column.
Eigen::VectorXd weight_vector(const MatrixInput& weights) {
  const Eigen::MatrixXd& w = values_of(weights, "weights");
  if (w.size() > 0 && w.rows() != 1 && w.cols() != 1) {
    throw InputError("the weights are " + std::to_string(w.rows()) + "x" + std::to_string(w.cols()) +
                         ": give one per row of X, as one column or one row",
                     Code::DataShape, "weights");
  }
  return Eigen::Map<const Eigen::VectorXd>(w.data(), w.size());
}

}  // namespace

NearestCorrelationOptions NearestRequest::correlation_options() const {
  NearestCorrelationOptions options;
  options.floor = floor();
  options.weights = weight_vector(weights);
  options.alpha = alpha.value_or(options.alpha);
  options.max_iterations = max_iterations.value_or(options.max_iterations);
  options.tolerance = tolerance.value_or(options.tolerance);
  return options;
}

NearestLowRankOptions NearestRequest::low_rank_options() const {
  NearestLowRankOptions options;
  options.weights = weight_vector(weights);
  options.keep_diagonal = keep_diag && !corr;
  options.max_iterations = max_iterations.value_or(options.max_iterations);
  options.tolerance = tolerance.value_or(options.tolerance);
  options.form_x = !factors_only;
  return options;
}

DiagonalRule NearestRequest::diagonal_rule() const {
  return corr ? DiagonalRule::Unit : keep_diag ? DiagonalRule::Kept : DiagonalRule::Free;
}

const std::vector<OptionSpec<NearestRequest>>& nearest_option_table() {
  static const std::vector<OptionSpec<NearestRequest>> table = make_table();
  return table;
}

void check_nearest_request(const std::vector<std::string_view>& given,
                           const std::vector<std::string_view>& unavailable) {
  check_option_combination(nearest_option_table(), given, unavailable);
}

namespace {

NearestResult repair(const Eigen::Ref<const Eigen::MatrixXd>& C, const NearestRequest& request) {
  if (request.factors > 0) return nearest_correlation_factors(C, request.factors, request.low_rank_options());
  if (request.rank > 0) return nearest_correlation_rank(C, request.rank, request.low_rank_options());
  if (request.structured()) {
    NearestStructure structure;
    structure.fixed = values_of(request.fixed, "fixed");
    structure.index_base = request.fixed_index_base;
    structure.h_weights = values_of(request.h_weights, "h_weights");
    return nearest_structured(C, request.diagonal_rule(), structure, request.correlation_options());
  }
  if (!request.newton()) {
    NearestResult result = nearest_spd(C, request.floor());
    result.method = "eigenvalue clip";
    return result;
  }
  const NearestCorrelationOptions options = request.correlation_options();
  NearestResult result = request.corr        ? nearest_correlation(C, options)
                         : request.keep_diag ? nearest_keep_diagonal(C, options)
                                             : nearest_via_correlation(C, options);
  result.method = "Qi-Sun Newton";
  return result;
}

}  // namespace

NearestResult nearest(const Eigen::Ref<const Eigen::MatrixXd>& C, const NearestRequest& request) {
  if (!request.min_diag) return repair(C, request);
  std::vector<Warning> raised;
  const Eigen::MatrixXd floored = raise_variances(C, *request.min_diag, raised);
  NearestResult result = repair(floored, request);
  result.warnings.insert(result.warnings.begin(), raised.begin(), raised.end());
  return result;
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

// A matrix option's file (`fixed`'s mask or pairs, `h_weights`' H), named by the same variables as
// X when it has names (a labelled matrix as pandas writes one: reordered to X's order), checked by
// the library's rule for an n x n matrix (NearestStructure::is_valid) with the file named.
Eigen::MatrixXd read_structure(const std::string& path, std::string_view option, Eigen::Index n, DiagonalRule rule,
                               const std::vector<std::string>& x_names, const io::ReadOptions& read,
                               std::vector<Warning>& warnings) {
  io::LabelledTable labelled = io::read_labelled_table(path, read);
  warnings.insert(warnings.end(), labelled.table.warnings.begin(), labelled.table.warnings.end());
  const std::vector<std::string> names = variable_names(labelled, path, &warnings);
  Eigen::MatrixXd M = std::move(labelled.table.values);
  if (M.rows() == n && M.cols() == n) {  // a mask or weights (not a list of pairs)
    std::string error;
    std::optional<Eigen::MatrixXd> aligned = aligned_by_name(M, names, x_names, &error);
    if (!aligned) throw io::DataError(path, 0, 0, error, Code::DataShape);
    M = std::move(*aligned);
  }
  NearestStructure structure;
  (option == "fixed" ? structure.fixed : structure.h_weights) = M;
  std::string error;
  if (!structure.is_valid(n, rule, &error)) {
    // A matrix of another size is DataShape (`fixed` also takes k index pairs: k x 2), its values DataValue.
    const bool square = M.rows() == n && M.cols() == n;
    const bool shape = option == "fixed" ? !square && M.cols() != 2 : !square;
    throw io::DataError(path, 0, 0, error, shape ? Code::DataShape : Code::DataValue);
  }
  return M;
}

}  // namespace

const std::vector<OptionSpec<NearestCommand>>& nearest_command_table() {
  static const std::vector<OptionSpec<NearestCommand>> table = make_command_table();
  return table;
}

NearestRun run_nearest(NearestCommand command) {
  NearestRun run;
  run.repair = std::move(command.repair);
  Eigen::MatrixXd X;
  const std::string& path = command.matrix.path;
  if (command.matrix.from_file()) {
    // With the labels of an index column: the names of X's variables (df.cov().to_csv()). NaN and
    // Inf are read, to be named below by the variables they pair.
    io::ReadOptions read = command.read;
    read.allow_nonfinite = true;
    io::LabelledTable labelled = io::read_labelled_table(path, read);
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
    if (const std::optional<detail::NonfiniteEntry> e = detail::first_nonfinite(X)) {
      const bool named = run.names.size() == static_cast<std::size_t>(X.rows());
      const std::string where = named ? "(" + run.names[static_cast<std::size_t>(e->row)] + ", " +
                                            run.names[static_cast<std::size_t>(e->column)] + "), "
                                      : std::string();
      throw io::DataError(path, 0, 0,
                          std::string(e->what) + " at " + where + "row " + std::to_string(e->row + 1) + ", column " +
                              std::to_string(e->column + 1) + detail::kNonfiniteCause);
    }
  } else {
    X = std::move(command.matrix.values);  // at n = 10,000, a copy would be 800 MB
  }
  if (run.repair.weights.from_file()) {
    const Eigen::MatrixXd W = io::read_matrix(run.repair.weights.path, command.read);
    const Eigen::Index n = X.rows();
    if (W.size() != n || (W.rows() != 1 && W.cols() != 1)) {
      throw io::DataError(run.repair.weights.path, 0, 0,
                          "the weights are " + std::to_string(W.rows()) + "x" + std::to_string(W.cols()) +
                              ": give " + std::to_string(n) + " numbers (one per row of X) as one column or one row",
                          Code::DataShape);
    }
    NearestCorrelationOptions weighted;
    weighted.weights = Eigen::Map<const Eigen::VectorXd>(W.data(), n);
    std::string error;
    if (!weighted.is_valid(n, &error)) throw io::DataError(run.repair.weights.path, 0, 0, error, Code::DataValue);
    run.repair.weights = MatrixInput{{}, W};
  }
  for (MatrixInput* input : {&run.repair.fixed, &run.repair.h_weights}) {
    if (!input->from_file()) continue;
    const std::string_view option = input == &run.repair.fixed ? "fixed" : "h_weights";
    *input = MatrixInput{{}, read_structure(input->path, option, X.rows(), run.repair.diagonal_rule(), run.names,
                                            command.read, run.warnings)};
    // A file's pairs count from 1 whoever names the file (Python counts its arrays' from 0).
    if (option == "fixed") run.repair.fixed_index_base = 1;
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
