// `physical regress`'s option table, and the regression from files.
#include <string>

#include "physical/common_options.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit::physical {

namespace {

using Spec = OptionSpec<RegressRequest>;

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec y = detail::text_option<RegressRequest>("y", "Y", "", "",
                                               "The stacked regressor (rows = samples x outputs; 10 K body columns, "
                                               "then any extra columns)",
                                               "");
  y.type = OptionType::File;
  y.positional = true;
  y.required = true;
  y.set = [](RegressRequest& r, const OptionValue& v) { r.y_path = std::get<std::string>(v); };
  table.push_back(y);
  Spec tau = detail::text_option<RegressRequest>("tau", "TAU", "", "", "The stacked outputs (one column, Y's rows)", "");
  tau.type = OptionType::File;
  tau.positional = true;
  tau.required = true;
  tau.set = [](RegressRequest& r, const OptionValue& v) { r.tau_path = std::get<std::string>(v); };
  table.push_back(tau);
  Spec bodies;
  bodies.name = "bodies";
  bodies.cli = "--bodies";
  bodies.python = "bodies";
  bodies.type = OptionType::Integer;
  bodies.value_name = "K";
  bodies.help = "The number of rigid bodies: Y's first 10 K columns are their parameters, 10 per body (any "
                "further columns are unconstrained extra parameters such as friction)";
  bodies.default_text = "1";
  bodies.range = {1.0, 1e4};
  bodies.nullable = false;
  bodies.set = [](RegressRequest& r, const OptionValue& v) { r.bodies = int(std::get<std::int64_t>(v)); };
  bodies.get = [](const RegressRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.bodies}; };
  table.push_back(bodies);

  Spec order = detail::choice_option<RegressRequest>(
      "param_order", "--param-order", "param_order", {"urdf", "pinocchio"},
      "The order of each body's 10 columns: m, m c (x, y, z), then the inertia about the body frame's origin as "
      "urdf (xx, xy, xz, yy, yz, zz) or as pinocchio's toDynamicParameters (xx, xy, yy, xz, yz, zz)",
      "urdf");
  order.set = [](RegressRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const std::optional<ParamOrder> parsed = parse_param_order(name);
    if (!parsed) throw OptionError("`param_order` must be urdf or pinocchio, got '" + name + "'");
    r.param_order = *parsed;
  };
  order.get = [](const RegressRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.param_order)); };
  table.push_back(order);

  Spec unconstrained = detail::flag_option<RegressRequest>(
      "unconstrained", "--unconstrained", "unconstrained",
      "Ordinary least squares without the consistency constraint, for comparison (may return bodies that cannot "
      "exist)");
  unconstrained.excludes = {"prior"};
  unconstrained.set = [](RegressRequest& r, const OptionValue& v) { r.consistent = !std::get<bool>(v); };
  unconstrained.get = [](const RegressRequest& r) -> std::optional<OptionValue> { return !r.consistent; };
  table.push_back(unconstrained);

  Spec noise = detail::text_option<RegressRequest>(
      "noise_cov", "--noise-cov", "", "FILE",
      "The covariance of the noise in one sample's d outputs (a d x d matrix file): Y's and tau's rows come in "
      "samples of d consecutive rows, each sample's residual weighted by its inverse",
      "");
  noise.set = [](RegressRequest& r, const OptionValue& v) { r.noise_cov_path = std::get<std::string>(v); };
  table.push_back(noise);

  Spec prior = detail::text_option<RegressRequest>(
      "prior", "--prior", "", "FILE",
      "Prior bodies, e.g. from CAD (JSON: a list of K bodies {\"mass\", \"center_of_mass\", \"inertia\"} in each "
      "body's frame, inertia about the centre of mass): `prior_weight` times the log-determinant divergence of each "
      "body's pseudo-inertia from the prior's is added, which sets the parameters the data do not determine",
      "");
  prior.type = OptionType::File;
  prior.set = [](RegressRequest& r, const OptionValue& v) { r.prior_path = std::get<std::string>(v); };
  table.push_back(prior);

  Spec weight;
  weight.name = "prior_weight";
  weight.cli = "--prior-weight";
  weight.python = "prior_weight";
  weight.type = OptionType::Real;
  weight.value_name = "W";
  weight.help = "The prior's weight against the squared residuals divided by the unconstrained fit's residual "
                "variance";
  weight.default_text = "1";
  weight.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  weight.needs = {"prior"};
  weight.needs_message = "`prior_weight` weighs the prior: give `prior` as well";
  weight.set = [](RegressRequest& r, const OptionValue& v) { r.prior_weight = std::get<double>(v); };
  weight.get = [](const RegressRequest& r) -> std::optional<OptionValue> { return r.prior_weight; };
  table.push_back(weight);

  detail::add_solver_options(table, "500");
  detail::add_bootstrap_options(table, "Resample the samples N times for the parameters' standard errors and "
                                       "percentile intervals (each replicate refitted)");
  for (Spec& spec : output_options(&RegressRequest::output, {"json", "output"}, {"Print the result as JSON"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

}  // namespace

const std::vector<OptionSpec<RegressRequest>>& regress_option_table() {
  static const std::vector<OptionSpec<RegressRequest>> table = make_table();
  return table;
}

RegressResult regress_files(const std::string& y_path, const std::string& tau_path, RegressRequest request,
                            const io::ReadOptions& read) {
  const Eigen::MatrixXd Y = io::read_matrix(y_path, read);
  const Eigen::MatrixXd tau = io::read_matrix(tau_path, read);
  if (tau.cols() != 1 || tau.rows() != Y.rows()) {
    throw io::DataError(tau_path, 0, 0,
                        "tau is " + std::to_string(tau.rows()) + " x " + std::to_string(tau.cols()) +
                            ": give one column with Y's " + std::to_string(Y.rows()) + " rows (" + y_path + ")", Code::DataShape);
  }
  if (Y.cols() < 10 * request.bodies) {
    throw io::DataError(y_path, 0, 0,
                        "Y has " + std::to_string(Y.cols()) + " columns: `bodies` = " + std::to_string(request.bodies) +
                            " needs at least " + std::to_string(10 * request.bodies) +
                            " (10 per body, then any extra columns)", Code::DataShape);
  }
  if (!request.noise_cov_path.empty()) {
    request.noise_cov = io::read_matrix(request.noise_cov_path, read);
    std::string error;
    RegressRequest check;
    check.noise_cov = request.noise_cov;
    if (!check.is_valid(&error)) throw io::DataError(request.noise_cov_path, 0, 0, spell_options(error, Frontend::Library), Code::NoiseModel);
    if (Y.rows() % request.noise_cov.rows() != 0) {
      throw io::DataError(request.noise_cov_path, 0, 0,
                          "the noise covariance is " + std::to_string(request.noise_cov.rows()) + " x " +
                              std::to_string(request.noise_cov.rows()) + ", but Y's " + std::to_string(Y.rows()) +
                              " rows are not a whole number of samples of that many outputs", Code::NoiseModel);
    }
  }
  if (!request.prior_path.empty()) {
    request.prior = read_rigid_bodies(request.prior_path);
    if (static_cast<int>(request.prior.size()) != request.bodies) {
      throw io::DataError(request.prior_path, 0, 0,
                          "the prior has " + std::to_string(request.prior.size()) + " bodies, but `bodies` is " +
                              std::to_string(request.bodies), Code::DataShape);
    }
    RegressRequest check;
    check.bodies = request.bodies;
    check.prior = request.prior;
    std::string error;
    if (!check.is_valid(&error)) throw io::DataError(request.prior_path, 0, 0, error, Code::PhysicalData);
  }
  return regress(Y, tau, request);
}

void check_regress_request(const RegressRequest& /*request*/, const std::vector<std::string_view>& given) {
  check_option_combination(regress_option_table(), given);
}

RegressResult run_regress(const RegressRequest& request, const io::ReadOptions& read) {
  return regress_files(request.y_path, request.tau_path, request, read);
}

}  // namespace spdfit::physical
