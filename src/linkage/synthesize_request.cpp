// `linkage synthesize`'s option table and workflow (its renderings: render/linkage_synthesize_render.cpp).
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "render/linkage_render.hpp"
#include "interface/option_builders.hpp"
#include "render/json_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/linkage/pairs_file.hpp"
#include "spdfit/linkage/synthesize_request.hpp"

namespace spdfit::linkage {

namespace {

using SynthesizeSpec = OptionSpec<SynthesizeRequest>;

using detail::full_g;
using detail::in_radians;

// Python spells the options as the library names them, but for `rho` (its `steering=RHO`), and
// has no `steering` flag (rho implies it) and no `positions` (a report's layout). Its `radians`
// keyword, spelled out, converts every angle and passes this one for the pairs.
SynthesizeSpec synthesize_option(std::string_view name, std::string_view cli, OptionType type,
                                 std::string_view value_name, std::string_view help,
                                 std::string_view default_text = {}) {
  std::string_view python = name;
  if (name == "rho") python = "steering";
  if (name == "steering" || name == "positions") python = "";
  return spdfit::detail::option_entry<SynthesizeRequest>(name, cli, python, type, value_name, help, default_text);
}

std::vector<std::string_view> function_choices() {
  std::vector<std::string_view> out;
  for (const std::string& name : function_names()) out.push_back(name);
  return out;
}

std::vector<SynthesizeSpec> make_synthesize_table() {
  std::vector<SynthesizeSpec> table;
  const auto text = [](std::string SynthesizeRequest::*field) {
    return [field](SynthesizeRequest& r, const OptionValue& v) { r.*field = std::get<std::string>(v); };
  };
  const auto flag = [](bool SynthesizeRequest::*field) {
    return [field](SynthesizeRequest& r, const OptionValue& v) { r.*field = std::get<bool>(v); };
  };
  const auto matrix = [](MatrixInput SynthesizeRequest::*field) {
    return [field](SynthesizeRequest& r, const OptionValue& v) { r.*field = std::get<MatrixInput>(v); };
  };
  SynthesizeSpec pairs = synthesize_option("pairs", "--pairs", OptionType::Matrix, "FILE",
                                           "File of input-output pairs: columns psi, phi (degrees; a header row "
                                           "allowed)");
  pairs.set = matrix(&SynthesizeRequest::pairs);
  table.push_back(pairs);
  SynthesizeSpec weights = synthesize_option("weights", "--weights", OptionType::Matrix, "FILE",
                                             "File of one positive weight per pair (W in 1/2 d^T W d)");
  weights.set = matrix(&SynthesizeRequest::weights);
  table.push_back(weights);
  SynthesizeSpec radians = synthesize_option("radians", "--radians", OptionType::Flag, "",
                                             "The `pairs` angles are in radians");
  radians.set = flag(&SynthesizeRequest::radians);
  table.push_back(radians);
  SynthesizeSpec steering = synthesize_option("steering", "--steering", OptionType::Flag, "",
                                              "Prescribe the steering condition (eq. 3.5); needs `rho`");
  steering.set = flag(&SynthesizeRequest::steering);
  table.push_back(steering);
  SynthesizeSpec rho = synthesize_option("rho", "--rho", OptionType::Real, "RHO",
                                         "Steering: track / wheelbase (e.g. 0.5); implies `steering`");
  rho.set = [](SynthesizeRequest& r, const OptionValue& v) { r.rho = std::get<double>(v); };
  table.push_back(rho);
  SynthesizeSpec function = synthesize_option("function", "--function", OptionType::Choice, "NAME",
                                              "Prescribe y = f(x): linear, square, cube, sqrt, reciprocal, exp, ln, "
                                              "log10, sin, cos, tan");
  function.choices = function_choices();
  function.set = text(&SynthesizeRequest::function);
  table.push_back(function);
  SynthesizeSpec x_range = synthesize_option("x_range", "--x-range", OptionType::Range, "LO:HI",
                                             "`function`: the x range LO:HI");
  x_range.set = text(&SynthesizeRequest::x_range);
  table.push_back(x_range);
  SynthesizeSpec psi_range = synthesize_option("psi_range", "--psi-range", OptionType::Range, "LO:HI",
                                               "Input angle changes LO:HI (degrees) from the dial zero (`steering` "
                                               "default -30:30)");
  psi_range.set = text(&SynthesizeRequest::psi_range);
  table.push_back(psi_range);
  SynthesizeSpec phi_range = synthesize_option("phi_range", "--phi-range", OptionType::Range, "LO:HI",
                                               "`function`: output angle changes LO:HI (degrees)");
  phi_range.set = text(&SynthesizeRequest::phi_range);
  table.push_back(phi_range);
  SynthesizeSpec points = synthesize_option("points", "--points", OptionType::Integer, "N",
                                            "Number of prescribed positions", "21");
  points.range = {1.0, double(std::numeric_limits<int>::max())};
  points.nullable = false;
  points.set = [](SynthesizeRequest& r, const OptionValue& v) { r.points = int(std::get<std::int64_t>(v)); };
  points.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.points}; };
  table.push_back(points);
  SynthesizeSpec spacing = synthesize_option("spacing", "--spacing", OptionType::Choice, "",
                                             "Input spacing: uniform or chebyshev", "uniform");
  spacing.choices = {"uniform", "chebyshev"};
  spacing.nullable = false;
  spacing.set = [](SynthesizeRequest& r, const OptionValue& v) {
    r.spacing = std::get<std::string>(v) == "chebyshev" ? Spacing::Chebyshev : Spacing::Uniform;
  };
  spacing.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> {
    return std::string(r.spacing == Spacing::Chebyshev ? "chebyshev" : "uniform");
  };
  table.push_back(spacing);
  SynthesizeSpec alpha = synthesize_option("alpha", "--alpha", OptionType::Real, "DEG",
                                           "Input dial zero (degrees): psi = alpha + delta psi (default 0; "
                                           "`steering`: 90 - atan(rho/2))");
  alpha.set = [](SynthesizeRequest& r, const OptionValue& v) { r.alpha = std::get<double>(v); };
  table.push_back(alpha);
  SynthesizeSpec beta = synthesize_option("beta", "--beta", OptionType::Real, "DEG",
                                          "Output dial zero (degrees): phi = beta + delta phi (default 0; "
                                          "`steering`: 90 + atan(rho/2))");
  beta.set = [](SynthesizeRequest& r, const OptionValue& v) { r.beta = std::get<double>(v); };
  table.push_back(beta);
  SynthesizeSpec fit = synthesize_option("fit_dial_zeros", "--fit-dial-zeros", OptionType::Flag, "",
                                         "Also solve for alpha and beta (eq. 3.7); `alpha`/`beta` are then the start");
  fit.set = flag(&SynthesizeRequest::fit_dial_zeros);
  fit.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> { return r.fit_dial_zeros; };
  table.push_back(fit);
  // Python's (the command line always refines).
  SynthesizeSpec refine = synthesize_option("refine", "", OptionType::Boolean, "",
                                            "Refine the design-error solution by Gauss-Newton on the structural "
                                            "error (section 3.6)", "true");
  refine.nullable = false;
  refine.set = flag(&SynthesizeRequest::refine);
  refine.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> { return r.refine; };
  table.push_back(refine);
  SynthesizeSpec tolerance = synthesize_option("tolerance", "--tolerance", OptionType::Real, "",
                                               "Gauss-Newton stops when ||Delta k|| < this", "1e-10");
  tolerance.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  tolerance.nullable = false;
  tolerance.set = [](SynthesizeRequest& r, const OptionValue& v) { r.tolerance = std::get<double>(v); };
  tolerance.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> { return r.tolerance; };
  table.push_back(tolerance);
  SynthesizeSpec iterations = synthesize_option("max_iterations", "--max-iterations", OptionType::Integer, "",
                                                "Gauss-Newton iteration limit", "100");
  iterations.range = {1.0, double(std::numeric_limits<int>::max())};
  iterations.nullable = false;
  iterations.set = [](SynthesizeRequest& r, const OptionValue& v) { r.max_iterations = int(std::get<std::int64_t>(v)); };
  iterations.get = [](const SynthesizeRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.max_iterations}; };
  table.push_back(iterations);
  SynthesizeSpec threshold = synthesize_option("threshold", "--threshold", OptionType::Real, "",
                                               "Relative singular-value cut-off for S", "max(m,3)*eps, notes 3.8");
  threshold.range = {0.0, 1.0, false, true};
  threshold.set = [](SynthesizeRequest& r, const OptionValue& v) { r.threshold = std::get<double>(v); };
  table.push_back(threshold);
  SynthesizeSpec positions = synthesize_option("positions", "--positions", OptionType::Flag, "",
                                               "Also print every position: prescribed and generated phi");
  positions.set = flag(&SynthesizeRequest::positions);
  table.push_back(positions);
  for (SynthesizeSpec& spec : output_options(&SynthesizeRequest::output, {"json", "output"},
                                             {"Print the result as JSON", "Write to FILE instead of stdout"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

bool named(const std::vector<std::string_view>& given, std::string_view name) {
  for (std::string_view g : given) {
    if (g == name) return true;
  }
  return false;
}

}  // namespace

const std::vector<OptionSpec<SynthesizeRequest>>& synthesize_option_table() {
  static const std::vector<OptionSpec<SynthesizeRequest>> table = make_synthesize_table();
  return table;
}

SynthesisRun run_synthesize(const SynthesizeRequest& o, const std::vector<std::string_view>& given) {
  const auto usage = [](const std::string& message, const char* option = "") {
    return OptionError(message, Code::OptionConflict, option);
  };
  // `rho` implies `steering` (Python's steering=RHO; the command line's --steering --rho RHO).
  const bool steering = o.steering || o.rho.has_value();
  const int sources = o.pairs.given() + steering + !o.function.empty();
  if (sources != 1) throw usage("give exactly one of `pairs` FILE, `steering` or `function` NAME");
  const bool generated = !o.pairs.given();
  if (!generated && (named(given, "points") || named(given, "spacing") || named(given, "psi_range") ||
                     named(given, "phi_range") || named(given, "x_range"))) {
    throw usage("`points`, `spacing`, `x_range`, `psi_range` and `phi_range` describe a prescribed function; "
                "they do not apply to `pairs`");
  }
  if (o.radians && generated) throw usage("`radians` applies to the angles of a `pairs` file", "radians");

  SynthesisOptions options;
  options.fit_dial_zeros = o.fit_dial_zeros;
  options.refine = o.refine;
  options.gauss_newton.tolerance = o.tolerance;
  options.gauss_newton.max_iterations = o.max_iterations;
  if (o.threshold) {
    options.rank_tolerance = *o.threshold;
    options.gauss_newton.rank_tolerance = *o.threshold;
  }
  options.alpha = o.alpha ? std::optional<double>(in_radians(*o.alpha)) : std::nullopt;
  options.beta = o.beta ? std::optional<double>(in_radians(*o.beta)) : std::nullopt;

  SynthesisRun run;
  if (!generated) {
    PairsFileOptions file;
    file.radians = o.radians;
    file.min_pairs = o.fit_dial_zeros ? 5 : 3;
    if (o.pairs.from_file()) {
      run.pairs = read_pairs(o.pairs.path, file);
      run.source = o.pairs.path;
    } else {
      io::Table table;
      table.values = o.pairs.values;
      run.source = "the pairs given";
      run.pairs = pairs_from_table(table, "pairs", file);
    }
  } else if (steering) {
    if (!o.rho) throw usage("`steering` needs `rho` (track / wheelbase, e.g. 0.5)", "steering");
    if (!o.phi_range.empty() || !o.x_range.empty()) {
      throw usage("`steering` takes `psi_range` only: the output follows from the steering condition", "steering");
    }
    const auto [lo, hi] = o.psi_range.empty() ? std::make_pair(kSteeringPsiRange[0], kSteeringPsiRange[1])
                                              : parse_range(o.psi_range, "psi_range");
    if (!(lo < hi)) throw OptionError("`psi_range` must have LO < HI", Code::OptionValue, "psi_range");
    run.pairs = steering_pairs(*o.rho, in_radians(lo), in_radians(hi), o.points, o.spacing);
    if (!o.fit_dial_zeros && !o.alpha && !o.beta) {
      const DialZeros zeros = trapezoid_dial_zeros(*o.rho);
      options.alpha = zeros.alpha;
      options.beta = zeros.beta;
    }
    run.source = "steering condition (eq. 3.5), rho = " + full_g(*o.rho);
  } else {
    if (o.x_range.empty() || o.psi_range.empty() || o.phi_range.empty()) {
      throw usage("`function` needs `x_range`, `psi_range` and `phi_range`", "function");
    }
    const auto [x_lo, x_hi] = parse_range(o.x_range, "x_range");
    const auto [psi_lo, psi_hi] = parse_range(o.psi_range, "psi_range");
    const auto [phi_lo, phi_hi] = parse_range(o.phi_range, "phi_range");
    if (!(x_lo < x_hi)) throw OptionError("`x_range` must have LO < HI", Code::OptionValue, "x_range");
    try {
      run.pairs = function_pairs(o.function, x_lo, x_hi, in_radians(psi_lo), in_radians(psi_hi), in_radians(phi_lo),
                                 in_radians(phi_hi), o.points, o.spacing);
    } catch (const std::invalid_argument& e) {
      throw OptionError(std::string("`function`: ") + e.what(), Code::OptionValue, "function");
    }
    run.source = "y = " + o.function + "(x), x in [" + full_g(x_lo) + ", " + full_g(x_hi) + "]";
  }
  if (o.weights.from_file()) {
    run.weights = read_weights(o.weights.path, run.pairs.delta_psi.size());
  } else if (o.weights.given()) {
    run.weights = weights_from_matrix(o.weights.values, run.pairs.delta_psi.size(), "weights");
  }
  run.result = synthesize(run.pairs.delta_psi, run.pairs.delta_phi, run.weights, options);
  return run;
}

}  // namespace spdfit::linkage
