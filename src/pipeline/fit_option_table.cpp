// The fit's option table: each option declared once, with everything the front ends need.
#include "spdfit/fit_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "io/row_selection.hpp"
#include "pipeline/log_rows.hpp"
#include "robust/m_estimator.hpp"
#include "pipeline/noise_files.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/noise_model.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<FitRequest>;

// The largest --block-rows: a block of 2^24 rows of a few columns is already hundreds of MB.
constexpr double kMaxBlockRows = double(std::int64_t{1} << 24);

double real(const OptionValue& v) { return std::get<double>(v); }
std::int64_t integer(const OptionValue& v) { return std::get<std::int64_t>(v); }
bool boolean(const OptionValue& v) { return std::get<bool>(v); }
const std::string& text(const OptionValue& v) { return std::get<std::string>(v); }
const std::vector<double>& reals(const OptionValue& v) { return std::get<std::vector<double>>(v); }

// A noise input's value for the table's getters: nothing when not given.
std::optional<OptionValue> text_value(const std::string& value) {
  if (value.empty()) return std::nullopt;
  return value;
}
std::optional<OptionValue> matrix_value(const MatrixInput& value) {
  if (!value.given()) return std::nullopt;
  return value;
}
std::optional<OptionValue> list_value(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  return values;
}

// Every method but spde takes a noise model (spde's area criterion has none).
bool takes_noise_model(const FitRequest& r) { return r.method != Method::Spde; }
constexpr std::string_view kNoiseAppliesTo =
    "the methods with a noise model (its maximum-likelihood fit: auto or spd-tls; spde has none)";

// The options of a noise model's sources: one pair, not with noise_ratio (the model gives the ratio).
const std::vector<std::string_view> kNoiseOptions = {"noise",       "rest_a",      "rest_b",     "noise_std_a",
                                                     "noise_std_b", "noise_cov_a", "noise_cov_b", "rest_rows"};

// The options that `name`'s pair cannot be given with: noise_ratio and the other sources.
std::vector<std::string_view> noise_excludes(std::string_view name, std::string_view partner) {
  std::vector<std::string_view> out = {"noise_ratio"};
  for (std::string_view other : kNoiseOptions) {
    if (other != name && other != partner) out.push_back(other);
  }
  return out;
}

// One side of a pair of noise options (rest_a and rest_b, ...): the other side is needed too.
Spec noise_source(std::string_view name, std::string_view partner, std::string_view cli, OptionType type,
                  std::string_view value_name, std::string_view help, std::string_view needs_message) {
  Spec spec;
  spec.name = name;
  spec.cli = cli;
  spec.type = type;
  spec.value_name = value_name;
  spec.help = help;
  spec.applies = takes_noise_model;
  spec.applies_to = kNoiseAppliesTo;
  spec.needs = {partner};
  spec.needs_message = needs_message;
  spec.excludes = noise_excludes(name, partner);
  if (type == OptionType::RealList) spec.range = {0.0, std::numeric_limits<double>::infinity()};
  return spec;
}

std::vector<Spec> make_table() {
  std::vector<Spec> table;

  Spec rank;
  rank.name = "rank_tolerance";
  rank.cli = "--rank-tol";
  rank.python = "rank_tolerance";
  rank.type = OptionType::Real;
  rank.value_name = "NUMBER";
  rank.help = "Relative singular-value cut-off for numerical rank: sigma_i counts as zero when "
              "sigma_i <= tol * sigma_max, decided on A and B with their columns scaled to unit norm";
  rank.default_text = "max(m, n) eps";
  rank.range = {0.0, 1.0, false, true};
  rank.set = [](FitRequest& r, const OptionValue& v) { r.options.rank_tolerance = real(v); };
  rank.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    if (!r.options.rank_tolerance) return std::nullopt;
    return *r.options.rank_tolerance;
  };
  table.push_back(rank);

  Spec ratio;
  ratio.name = "noise_ratio";
  ratio.cli = "--noise-ratio";
  ratio.python = "noise_ratio";
  ratio.type = OptionType::Real;
  ratio.value_name = "NUMBER";
  ratio.help = "sigma_B / sigma_A, the noise in B relative to the noise in A, for the total least-squares "
               "methods (tls, tls-sym, tls-psd, spd-tls) and auto";
  ratio.default_text = "1";
  ratio.range = {0.0, std::numeric_limits<double>::infinity(), true, true};
  ratio.applies = [](const FitRequest& r) { return uses_noise_ratio(r.method); };
  ratio.applies_to = "the total least-squares methods and auto";
  ratio.set = [](FitRequest& r, const OptionValue& v) { r.options.noise_ratio = real(v); };
  ratio.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.noise_ratio; };
  table.push_back(ratio);

  Spec noise;
  noise.name = "noise";
  noise.python = "noise";
  noise.type = OptionType::Noise;
  noise.help = "The noise model: the covariances of the noise in each row of A and of B (NoiseModel). spd-tls and "
               "auto become the maximum-likelihood fit, psd-ls and procrustes weighted by B's noise, tls, tls-sym "
               "and tls-psd generalized total least squares. Default: equal noise in every column of A and B, "
               "in the units given";
  noise.applies = takes_noise_model;
  noise.applies_to = kNoiseAppliesTo;
  noise.excludes = noise_excludes("noise", "noise");
  noise.set = [](FitRequest& r, const OptionValue& v) {
    r.options.noise = *std::get<std::shared_ptr<const NoiseModel>>(v);
  };
  noise.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    if (!r.options.noise) return std::nullopt;
    return std::make_shared<const NoiseModel>(*r.options.noise);
  };
  table.push_back(noise);

  const std::string_view rest_pair = "`rest_a` and `rest_b` come together: the rows of A and of B recorded at rest";
  Spec rest_a = noise_source("rest_a", "rest_b", "--rest-a", OptionType::Matrix, "FILE",
                             "Rows of A recorded with the machine at rest (accelerations zero; any format A "
                             "takes, streamed): the noise model's Sigma_A is their sample covariance. "
                             "Default: equal noise in every column of A and B, in the units given",
                             rest_pair);
  rest_a.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.rest_a = std::get<MatrixInput>(v); };
  rest_a.get = [](const FitRequest& r) { return matrix_value(r.noise_inputs.rest_a); };
  table.push_back(rest_a);
  Spec rest_b = noise_source("rest_b", "rest_a", "--rest-b", OptionType::Matrix, "FILE",
                             "Rows of B recorded at rest, as many as `rest_a`'s (forces constant): Sigma_B is "
                             "their sample covariance about their mean, so a static load is not noise",
                             rest_pair);
  rest_b.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.rest_b = std::get<MatrixInput>(v); };
  rest_b.get = [](const FitRequest& r) { return matrix_value(r.noise_inputs.rest_b); };
  table.push_back(rest_b);

  const std::string_view std_pair =
      "`noise_std_a` and `noise_std_b` come together: give the noise of both sides (0: exact)";
  Spec std_a = noise_source("noise_std_a", "noise_std_b", "--noise-std-a", OptionType::RealList, "S",
                            "Standard deviation of the noise in A: one for every column, or one per column "
                            "(comma-separated); 0 means exact",
                            std_pair);
  std_a.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.std_a = reals(v); };
  std_a.get = [](const FitRequest& r) { return list_value(r.noise_inputs.std_a); };
  table.push_back(std_a);
  Spec std_b = noise_source("noise_std_b", "noise_std_a", "--noise-std-b", OptionType::RealList, "S",
                            "Standard deviation of the noise in B, as `noise_std_a`", std_pair);
  std_b.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.std_b = reals(v); };
  std_b.get = [](const FitRequest& r) { return list_value(r.noise_inputs.std_b); };
  table.push_back(std_b);

  const std::string_view cov_pair = "`noise_cov_a` and `noise_cov_b` come together: give the covariances of both";
  Spec cov_a = noise_source("noise_cov_a", "noise_cov_b", "--noise-cov-a", OptionType::Matrix, "FILE",
                            "File of Sigma_A, the covariance of the noise in a row of A (n x n, symmetric positive "
                            "semidefinite)",
                            cov_pair);
  cov_a.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.cov_a = std::get<MatrixInput>(v); };
  cov_a.get = [](const FitRequest& r) { return matrix_value(r.noise_inputs.cov_a); };
  table.push_back(cov_a);
  Spec cov_b = noise_source("noise_cov_b", "noise_cov_a", "--noise-cov-b", OptionType::Matrix, "FILE",
                            "File of Sigma_B, the covariance of the noise in a row of B (d x d)", cov_pair);
  cov_b.set = [](FitRequest& r, const OptionValue& v) { r.noise_inputs.cov_b = std::get<MatrixInput>(v); };
  cov_b.get = [](const FitRequest& r) { return matrix_value(r.noise_inputs.cov_b); };
  table.push_back(cov_b);

  // One log: the rows fitted and the rest segment from the data files themselves (in memory).
  const auto row_selection = [](std::string_view name, std::string_view cli, std::string_view help,
                                std::string FitRequest::*member) {
    Spec spec;
    spec.name = name;
    spec.cli = cli;
    spec.python = name;
    spec.type = OptionType::Rows;
    spec.value_name = "SPEC";
    spec.help = help;
    spec.excludes = {"stream"};
    spec.set = [member, name](FitRequest& r, const OptionValue& v) {
      // Row numbers or, with `time_col` (given in any order), times: checked as such when applied.
      io::detail::check_row_selection(std::get<std::string>(v), std::string(name), true);
      r.*member = std::get<std::string>(v);
    };
    spec.get = [member](const FitRequest& r) -> std::optional<OptionValue> {
      if ((r.*member).empty()) return std::nullopt;
      return r.*member;
    };
    return spec;
  };
  table.push_back(row_selection("rows", "--rows",
                                "Fit these rows of the data files: 1-based inclusive ranges and lists of their data "
                                "rows (601:, 1:5000,7001:), as `a_cols` numbers columns. Default: every row (but "
                                "`rest_rows`)",
                                &FitRequest::rows));
  Spec rest_rows = row_selection("rest_rows", "--rest-rows",
                                 "The rest segment from the data files themselves (1:600: the first 600 rows, "
                                 "recorded with the machine at rest): a noise model, as `rest_a` and `rest_b` give "
                                 "one from files of their own; `a_cols` and `b_cols` apply, and without `rows` the "
                                 "other rows are fitted",
                                 &FitRequest::rest_rows);
  rest_rows.applies = takes_noise_model;
  rest_rows.applies_to = kNoiseAppliesTo;
  rest_rows.excludes = noise_excludes("rest_rows", "rest_rows");
  rest_rows.excludes.push_back("stream");
  table.push_back(rest_rows);
  Spec time_col;
  time_col.name = "time_col";
  time_col.cli = "--time-col";
  time_col.python = "time_col";
  time_col.type = OptionType::Columns;
  time_col.value_name = "COL";
  time_col.help = "The log's time column (a header name or 1-based position, in the file of `a_cols` and `b_cols`): "
                  "`rows` and `rest_rows` are then ranges of its values (12.5:60, :0.995), in its units";
  time_col.needs = {"a_cols"};
  time_col.needs_message = "`time_col` is a column of the one log that `a_cols` and `b_cols` choose A and B from";
  time_col.excludes = {"stream"};
  time_col.set = [](FitRequest& r, const OptionValue& v) { r.time_col = text(v); };
  time_col.get = [](const FitRequest& r) { return text_value(r.time_col); };
  table.push_back(time_col);

  // Units: each column multiplied as the data are read (the noise model, in the files' units,
  // scaled with them: FitOptions::scale_a, scale_b).
  const auto unit_scale = [](std::string_view name, std::string_view cli, std::string_view help,
                             std::vector<double> FitOptions::*member) {
    Spec spec;
    spec.name = name;
    spec.cli = cli;
    spec.python = name;
    spec.type = OptionType::RealList;
    spec.value_name = "F";
    spec.help = help;
    spec.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
    spec.set = [member](FitRequest& r, const OptionValue& v) { r.options.*member = reals(v); };
    spec.get = [member](const FitRequest& r) { return list_value(r.options.*member); };
    return spec;
  };
  table.push_back(unit_scale("scale_a", "--scale-a",
                             "The factor A's columns are multiplied by as they are read: one for every column, or "
                             "one per column (comma-separated), for data logged in other units (accelerations in "
                             "g: 9.80665); rest rows and noise standard deviations are in the files' units and "
                             "are scaled with them. Default: as given",
                             &FitOptions::scale_a));
  table.push_back(unit_scale("scale_b", "--scale-b",
                             "The factor B's columns are multiplied by as they are read, as `scale_a` (forces "
                             "logged in kN: 1000)",
                             &FitOptions::scale_b));

  Spec offsets;
  offsets.name = "offsets";
  offsets.cli = "--offsets";
  offsets.python = "offsets";
  offsets.type = OptionType::Choice;
  offsets.value_name = "none|estimate|rest";
  offsets.choices = {"none", "estimate", "rest"};
  offsets.help = "Constant offsets in the columns of A and B (a static load in untared forces, a sensor's bias): "
                 "estimate fits A X + 1 c^T ~= B (the data centred by their column means; c is reported), rest "
                 "subtracts the means of the rows recorded at rest (those the noise model is made from), none "
                 "takes the data as given";
  offsets.default_text = "none";
  offsets.set = [](FitRequest& r, const OptionValue& v) {
    r.options.offsets = offsets_named(std::get<std::string>(v)).value_or(Offsets::None);  // a choice: named
  };
  offsets.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::string(to_string(r.options.offsets));
  };
  offsets.nullable = false;
  table.push_back(offsets);

  Spec robust;
  robust.name = "robust";
  robust.cli = "--robust";
  robust.python = "robust";
  robust.type = OptionType::Choice;
  robust.value_name = "none|huber|tukey";
  robust.choices = {"none", "huber", "tukey"};
  robust.help = "A robust fit: rows reweighted by their residual, whitened by the noise model (an M-estimator). "
                "huber for gross errors in B, tukey (from least trimmed squares) also for wrong values in A; "
                "in memory, every method but spde";
  robust.default_text = "none";
  robust.applies = [](const FitRequest& r) { return detail::robust_applies(r.method); };
  robust.applies_to = "every method but spde";
  robust.excludes = {"stream"};
  robust.set = [](FitRequest& r, const OptionValue& v) {
    r.options.robust = robust_loss_named(std::get<std::string>(v)).value_or(RobustLoss::None);  // a choice: named
  };
  robust.get = [](const FitRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.options.robust)); };
  robust.nullable = false;
  table.push_back(robust);

  Spec tuning;
  tuning.name = "robust_tuning";
  tuning.cli = "--robust-tuning";
  tuning.python = "robust_tuning";
  tuning.type = OptionType::Real;
  tuning.value_name = "K";
  tuning.help = "The robust loss's constant, in standard deviations of a row's whitened residual norm (default: "
                "95% of least squares' efficiency at Gaussian noise; one column of B: Huber 1.345, Tukey 4.685)";
  tuning.range = {0.0, std::numeric_limits<double>::infinity(), true, true};
  tuning.needs = {"robust"};
  tuning.needs_message = "`robust_tuning` is the constant of `robust`'s loss: give `robust` huber or tukey as well";
  tuning.set = [](FitRequest& r, const OptionValue& v) { r.options.robust_tuning = real(v); };
  tuning.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    if (!r.options.robust_tuning) return std::nullopt;
    return *r.options.robust_tuning;
  };
  table.push_back(tuning);

  Spec iterations;
  iterations.name = "max_iterations";
  iterations.cli = "--max-iter";
  iterations.python = "max_iter";
  iterations.type = OptionType::Integer;
  iterations.value_name = "N";
  iterations.help = "Iteration limit of spd-tls, psd-ls and auto; then the best iterate, with a warning";
  iterations.default_text = "200";
  iterations.range = {1.0, 1e6};
  iterations.applies = [](const FitRequest& r) { return uses_max_iterations(r.method); };
  iterations.applies_to = "the iterative methods";
  iterations.set = [](FitRequest& r, const OptionValue& v) { r.options.max_iterations = int(integer(v)); };
  iterations.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.max_iterations};
  };
  table.push_back(iterations);

  Spec floor;
  floor.name = "min_eig";
  floor.cli = "--min-eig";
  floor.python = "min_eig";
  floor.type = OptionType::Real;
  floor.value_name = "NUMBER";
  floor.help = "psd-ls: the floor epsilon of X >= epsilon I (0: positive semidefinite)";
  floor.default_text = "0";
  floor.range = {0.0, std::numeric_limits<double>::infinity()};
  floor.applies = [](const FitRequest& r) { return uses_min_eig(r.method); };
  floor.set = [](FitRequest& r, const OptionValue& v) { r.options.min_eig = real(v); };
  floor.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.min_eig; };
  table.push_back(floor);

  Spec bootstrap;
  bootstrap.name = "bootstrap";
  bootstrap.cli = "--bootstrap";
  bootstrap.python = "bootstrap";
  bootstrap.type = OptionType::Integer;
  bootstrap.value_name = "N";
  bootstrap.help = "Resample the rows N times for standard errors, an interval (`interval`) and the bias of "
                   "every entry of X (auto: refitting the method it chose)";
  bootstrap.default_text = "0";
  bootstrap.range = {0.0, 1e7};
  bootstrap.set = [](FitRequest& r, const OptionValue& v) { r.options.bootstrap = int(integer(v)); };
  bootstrap.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.bootstrap};
  };
  bootstrap.nullable = false;
  table.push_back(bootstrap);

  Spec confidence;
  confidence.name = "confidence";
  confidence.cli = "--confidence";
  confidence.python = "confidence";
  confidence.type = OptionType::Real;
  confidence.value_name = "FRACTION";
  confidence.help = "The bootstrap intervals' level, a fraction";
  confidence.default_text = "0.95";
  confidence.range = {0.0, 1.0, true, true};
  confidence.needs = {"bootstrap"};
  confidence.needs_message = "`confidence` applies to the bootstrap: give `bootstrap` N as well";
  confidence.set = [](FitRequest& r, const OptionValue& v) { r.options.confidence = real(v); };
  confidence.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.confidence; };
  table.push_back(confidence);

  Spec interval;
  interval.name = "interval";
  interval.cli = "--interval";
  interval.python = "interval";
  interval.type = OptionType::Choice;
  interval.value_name = "auto|percentile|basic|normal";
  interval.choices = {"auto", "percentile", "basic", "normal"};
  interval.help = "The bootstrap interval of each entry: percentile (the replicates' quantiles), basic (those "
                  "reflected about the estimate, which corrects its bias: better where X is near singular), "
                  "normal (the bias-corrected estimate -+ z standard errors) or auto: basic where X, or at "
                  "least 10% of the replicates, is singular (on the boundary of the cone), else percentile; "
                  "the result's interval type says which";
  interval.default_text = "auto";
  interval.needs = {"bootstrap"};
  interval.needs_message = "`interval` applies to the bootstrap: give `bootstrap` N as well";
  interval.set = [](FitRequest& r, const OptionValue& v) {
    r.options.interval = bootstrap_interval_named(std::get<std::string>(v)).value_or(BootstrapInterval::Auto);
  };
  interval.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::string(to_string(r.options.interval));
  };
  interval.nullable = false;
  table.push_back(interval);

  Spec seed;
  seed.name = "seed";
  seed.cli = "--seed";
  seed.python = "seed";
  seed.type = OptionType::Integer;
  seed.value_name = "N";
  seed.help = "The bootstrap's seed; the numbers depend on nothing else";
  seed.default_text = "1";
  seed.range = {0.0, double(std::numeric_limits<std::int64_t>::max())};
  seed.needs = {"bootstrap"};
  seed.needs_message = "`seed` applies to the bootstrap: give `bootstrap` N as well";
  seed.set = [](FitRequest& r, const OptionValue& v) { r.options.seed = std::uint64_t(integer(v)); };
  seed.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return static_cast<std::int64_t>(r.options.seed);
  };
  table.push_back(seed);

  Spec threads;
  threads.name = "threads";
  threads.cli = "--threads";
  threads.python = "threads";
  threads.type = OptionType::Integer;
  threads.value_name = "N";
  threads.help = "Threads for streaming and the bootstrap (0: one per core); the result does not depend on it";
  threads.default_text = "0";
  threads.range = {0.0, 1024.0};
  threads.needs = {"stream", "bootstrap"};
  threads.needs_message = "`threads` applies to `stream` and `bootstrap`: give one of them, or leave `threads` out";
  threads.set = [](FitRequest& r, const OptionValue& v) { r.options.threads = unsigned(integer(v)); };
  threads.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.threads};
  };
  threads.nullable = false;
  table.push_back(threads);

  Spec reported;
  reported.name = "reported_diagnostics";
  reported.python = "reported_diagnostics";
  reported.type = OptionType::Boolean;
  reported.help = "False skips the diagnostics that neither X nor a warning needs, at large n most of the time "
                  "beyond the estimate: noise_sigma and area_criterion are then None, residual_norm and "
                  "cond_b_scaled 0, and cond_a_scaled 0 unless A may be ill-conditioned enough for its warning";
  reported.default_text = "True";
  reported.set = [](FitRequest& r, const OptionValue& v) { r.options.reported_diagnostics = boolean(v); };
  reported.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.reported_diagnostics; };
  reported.nullable = false;
  table.push_back(reported);

  Spec stream;
  stream.name = "stream";
  stream.cli = "--stream";
  stream.type = OptionType::Flag;
  stream.help = "Read A and B a block of rows at a time (memory O(threads x block-rows x n + n^2) whatever the "
                "number of rows; same estimate to rounding)";
  stream.set = [](FitRequest& r, const OptionValue& v) { r.stream = boolean(v); };
  stream.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.stream; };
  stream.nullable = false;
  table.push_back(stream);

  const std::string_view cols_pair =
      "`a_cols` and `b_cols` come together: the columns of A and of B in the one file";
  Spec a_cols;
  a_cols.name = "a_cols";
  a_cols.cli = "--a-cols";
  a_cols.python = "a_cols";
  a_cols.type = OptionType::Columns;
  a_cols.value_name = "COLUMNS";
  a_cols.help = "A and B from one file: A's columns by header name or 1-based position (digits are positions), "
                "inclusive ranges and lists: acc1:acc6, 2:7, 1,3,5, 2:4,F1; the other columns are ignored";
  a_cols.needs = {"b_cols"};
  a_cols.needs_message = cols_pair;
  a_cols.set = [](FitRequest& r, const OptionValue& v) { r.a_cols = text(v); };
  a_cols.get = [](const FitRequest& r) { return text_value(r.a_cols); };
  table.push_back(a_cols);
  Spec b_cols;
  b_cols.name = "b_cols";
  b_cols.cli = "--b-cols";
  b_cols.python = "b_cols";
  b_cols.type = OptionType::Columns;
  b_cols.value_name = "COLUMNS";
  b_cols.help = "B's columns in the same file, as `a_cols` (no column in both)";
  b_cols.needs = {"a_cols"};
  b_cols.needs_message = cols_pair;
  b_cols.set = [](FitRequest& r, const OptionValue& v) { r.b_cols = text(v); };
  b_cols.get = [](const FitRequest& r) { return text_value(r.b_cols); };
  table.push_back(b_cols);

  Spec block;
  block.name = "block_rows";
  block.cli = "--block-rows";
  block.python = "block_rows";
  block.type = OptionType::Integer;
  block.value_name = "N";
  block.help = "Rows per block when streaming";
  block.default_text = "32768";
  block.range = {1.0, kMaxBlockRows};
  block.needs = {"stream"};
  block.set = [](FitRequest& r, const OptionValue& v) { r.block_rows = Eigen::Index(integer(v)); };
  block.get = [](const FitRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.block_rows}; };
  block.nullable = false;
  table.push_back(block);

  return table;
}

}  // namespace

const std::vector<OptionSpec<FitRequest>>& fit_option_table() {
  static const std::vector<OptionSpec<FitRequest>> table = make_table();
  return table;
}

const std::vector<std::string_view>& noise_option_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out = {"noise_ratio"};
    out.insert(out.end(), kNoiseOptions.begin(), kNoiseOptions.end());
    return out;
  }();
  return names;
}

bool FitRequest::is_valid(std::string* error) const { return options_in_range(*this, fit_option_table(), error); }

void check_fit_request(const FitRequest& request, const std::vector<std::string_view>& given) {
  std::vector<std::pair<std::string, FitRequest>> methods;
  for (Method m : kSelectableMethods) {
    FitRequest other;
    other.method = m;
    methods.emplace_back(std::string(to_string(m)), other);
  }
  for (std::string_view name : given) {
    const OptionSpec<FitRequest>* spec = find_option(fit_option_table(), name);
    if (spec == nullptr) continue;
    if (auto why = misplaced_option(*spec, request, methods, to_string(request.method))) throw OptionError(*why);
  }
  check_option_combination(fit_option_table(), given);
}

}  // namespace spdfit
