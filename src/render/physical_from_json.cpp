// The physical results read back from the JSON their to_json wrote: the hexapod's physical
// estimate, an inertia repair, a physical regression, a payload's estimate and pose design, the
// physical experiment. Each reads every key its to_json writes (Contract: non-finite numbers are
// null and read as NaN), so that to_json(from_json(text)) == text; fields to_json does not write
// (the data-sized residuals, the candidates' rows) keep their defaults.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/fit_result_json.hpp"
#include "render/json_values.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit {

namespace {

using detail::field;
using detail::Json;
using detail::optional_field;
using detail::value_from;

// One document's readers, naming the class and the key in every error.
class Reader {
 public:
  Reader(const Json& object, std::string type) : object_(object), type_(std::move(type)) {}

  const Json& at(const char* key) const { return field(object_, key, type_); }
  const Json* find(const char* key) const { return optional_field(object_, key); }
  Reader child(const char* key) const { return Reader(at(key), type_ + " " + key); }
  const std::string& type() const { return type_; }

  double number(const char* key) const { return detail::number_from(at(key), what(key)); }
  Eigen::VectorXd vector(const char* key) const { return detail::vector_from(at(key), what(key)); }
  Eigen::Vector3d vector3(const char* key) const {
    const Eigen::VectorXd v = vector(key);
    if (v.size() != 3) throw std::invalid_argument(what(key) + ": expected 3 numbers, got " + std::to_string(v.size()));
    return v;
  }
  /// A matrix; null (a matrix the estimate does not determine) reads as rows x cols of NaN.
  Eigen::MatrixXd matrix(const char* key, Eigen::Index rows = 0, Eigen::Index cols = 0) const {
    if (at(key).is_null() && rows > 0) {
      return Eigen::MatrixXd::Constant(rows, cols, std::numeric_limits<double>::quiet_NaN());
    }
    return detail::matrix_from(at(key), what(key), rows);
  }
  Eigen::Matrix3d matrix3(const char* key) const {
    const Eigen::MatrixXd M = matrix(key, 3, 3);
    if (M.rows() != 3 || M.cols() != 3) throw std::invalid_argument(what(key) + ": expected a 3 x 3 matrix");
    return M;
  }
  template <typename T>
  T value(const char* key) const {
    return value_from<T>(object_, key, type_);
  }
  Status status() const {
    const auto name = value<std::string>("status");
    for (Status s : {Status::NotComputed, Status::Success, Status::NumericalFailure}) {
      if (name == to_string(s)) return s;
    }
    throw std::invalid_argument(type_ + ": unknown status '" + name + "'");
  }
  /// An enum by its name, through the library's parser for it.
  template <typename Parse>
  auto named(const char* key, Parse parse) const {
    const auto name = value<std::string>(key);
    const auto parsed = parse(name);
    if (!parsed) throw std::invalid_argument(what(key) + ": unknown value '" + name + "'");
    return *parsed;
  }
  std::vector<Warning> warnings() const { return detail::warnings_from(object_, type_); }
  std::string error() const { return find("error") ? value<std::string>("error") : std::string(); }

 private:
  std::string what(const char* key) const { return type_ + " '" + key + "'"; }
  const Json& object_;
  std::string type_;
};

physical::Certificate certificate_from(const Reader& c) {
  physical::Certificate out;
  out.stationarity = c.number("stationarity");
  out.primal_min_eig = c.number("primal_min_eig");
  out.dual_min_eig = c.number("dual_min_eig");
  out.complementarity = c.number("complementarity");
  out.duality_gap = c.number("duality_gap");
  return out;
}

std::vector<physical::UndeterminedCombination> undetermined_from(const Reader& r) {
  std::vector<physical::UndeterminedCombination> out;
  const Json& list = r.at("undetermined");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Reader u(list[i], r.type() + " undetermined[" + std::to_string(i) + "]");
    out.push_back({u.value<std::vector<std::string>>("parameters"), u.vector("coefficients"),
                   u.value<std::string>("combination")});
  }
  return out;
}

// A parameter group of the payload's uncertainty (standard errors or an interval's bound): the
// keys of to_json's group_json, each into its own Interval's member.
void payload_group_from(const Reader& g, payload::PayloadEstimate::Bootstrap& b, Eigen::MatrixXd payload::Interval::*m) {
  b.mass.*m = Eigen::MatrixXd::Constant(1, 1, g.number("mass"));
  b.center_of_mass.*m = g.vector3("center_of_mass");
  b.inertia.*m = g.matrix3("inertia");
  b.principal_moments.*m = g.vector3("principal_moments");
  b.force_bias.*m = g.vector3("force_bias");
  b.torque_bias.*m = g.vector3("torque_bias");
}

// The hexapod's bootstrap groups (physical_render's entries()): one member of EntryUncertainty.
void physical_group_from(const Reader& g, hexapod::PhysicalBootstrap& b, Eigen::MatrixXd hexapod::EntryUncertainty::*m) {
  b.mass.*m = Eigen::MatrixXd::Constant(1, 1, g.number("mass"));
  b.center_of_mass.*m = g.vector("center_of_mass");
  b.inertia.*m = g.matrix("inertia");
  b.principal_moments.*m = g.vector("principal_moments");
  b.strut_mass.*m = g.at("strut_mass").is_array() ? Eigen::MatrixXd(g.vector("strut_mass"))
                                                  : Eigen::MatrixXd::Constant(1, 1, g.number("strut_mass"));
  b.M_p.*m = g.matrix("M_p");
}

}  // namespace

template <>
InertiaRepairResult from_json<InertiaRepairResult>(const std::string& text) {
  const Json document = detail::parse_object(text, "InertiaRepairResult");
  const Reader r(document, "InertiaRepairResult");
  InertiaRepairResult out;
  out.repaired.mass = r.number("mass");
  out.repaired.center_of_mass = r.vector3("center_of_mass");
  out.repaired.inertia = r.matrix3("inertia");
  out.changed = r.value<bool>("changed");
  out.distance = r.number("distance");
  const Reader c = r.child("certificate");
  out.certificate = {c.number("primal_min_eig"), c.number("dual_min_eig"), c.number("complementarity")};
  out.floor = r.number("min_eig");
  out.principal_moments = r.vector3("principal_moments");
  out.principal_moments_before = r.vector3("principal_moments_before");
  out.second_moments_before = r.vector3("second_moments_before");
  out.metric = r.named("metric", parse_inertia_metric);
  out.warnings = r.warnings();
  // The input's mass and centre of mass are the repair's (it keeps them); its inertia is not written.
  out.input.mass = out.repaired.mass;
  out.input.center_of_mass = out.repaired.center_of_mass;
  return out;
}

template <>
payload::DesignResult from_json<payload::DesignResult>(const std::string& text) {
  const Json document = detail::parse_object(text, "payload::DesignResult");
  const Reader r(document, "payload::DesignResult");
  payload::DesignResult out;
  out.criterion = r.named("criterion", payload::parse_design_criterion);
  out.poses = r.value<int>("poses");
  out.candidates = r.value<Eigen::Index>("candidates");
  for (Eigen::Index row : r.value<std::vector<Eigen::Index>>("chosen")) out.chosen.push_back(row - 1);
  out.score.log_det = r.number("log_det");
  out.score.condition = r.number("condition");
  out.score.se_mass = r.number("se_mass");
  out.score.se_center_of_mass = r.vector3("se_center_of_mass");
  out.score.se_center_of_mass_norm = r.number("se_center_of_mass_norm");
  const Reader random = r.child("random");
  out.random = random.value<int>("choices");
  out.random_log_det = random.vector3("log_det");
  out.random_se_mass = random.vector3("se_mass");
  out.random_se_center_of_mass = random.vector3("se_center_of_mass_norm");
  out.random_condition = random.vector3("condition");
  out.beats_random = random.number("beats");
  out.distinct_candidates = r.value<Eigen::Index>("distinct_candidates");
  out.warnings = r.warnings();
  return out;
}

template <>
payload::PayloadEstimate from_json<payload::PayloadEstimate>(const std::string& text) {
  const Json document = detail::parse_object(text, "payload::PayloadEstimate");
  const Reader r(document, "payload::PayloadEstimate");
  payload::PayloadEstimate out;
  out.status = r.status();
  out.warnings = r.warnings();
  if (!out.ok()) {
    out.message = r.error();
    return out;
  }
  const std::string model = r.value<std::string>("model");
  if (model != "static" && model != "moving") throw std::invalid_argument(r.type() + ": unknown model '" + model + "'");
  out.moving = model == "moving";
  out.criterion = r.named("criterion", payload::parse_criterion);
  out.consistent_requested = r.value<bool>("consistent");
  out.wrench_sign = r.named("wrench_sign", payload::parse_wrench_sign);
  out.frame = r.named("frame", payload::parse_wrench_frame);
  out.samples = r.value<Eigen::Index>("samples");
  out.mass = r.number("mass");
  out.center_of_mass = r.vector3("center_of_mass");
  out.inertia = r.matrix3("inertia");
  out.inertia_origin = r.matrix3("inertia_origin");
  out.principal.moments = r.vector3("principal_moments");
  out.principal.axes = r.matrix3("principal_axes");
  out.force_bias = r.vector3("force_bias");
  out.torque_bias = r.vector3("torque_bias");
  const Reader se = r.child("standard_errors");
  out.mass_se = se.number("mass");
  out.center_of_mass_se = se.vector3("center_of_mass");
  out.inertia_se = se.matrix3("inertia");
  out.principal_moments_se = se.vector3("principal_moments");
  out.force_bias_se = se.vector3("force_bias");
  out.torque_bias_se = se.vector3("torque_bias");
  out.names = r.value<std::vector<std::string>>("names");
  out.parameters = r.vector("parameters");
  out.standard_errors = r.vector("parameter_standard_errors");
  const Eigen::VectorXd rms = r.vector("residual_rms");
  if (rms.size() != 6) throw std::invalid_argument(r.type() + " 'residual_rms': expected 6 numbers");
  out.residual_rms = rms;
  out.identifiability.parameters = static_cast<Eigen::Index>(out.names.size());
  out.identifiability.condition = r.number("condition");
  out.identifiability.rank = r.value<Eigen::Index>("rank");
  out.identifiability.undetermined = undetermined_from(r);
  out.unconstrained_mass = r.number("unconstrained_mass");
  out.unconstrained_mass_se = r.number("unconstrained_mass_se");
  out.criterion_value = r.number("criterion_value");
  out.pseudo_inertia_min_eig = r.number("pseudo_inertia_min_eig");
  out.physically_consistent = r.value<bool>("physically_consistent");
  out.constraint_active = r.value<bool>("constraint_active");
  out.certificate = certificate_from(r.child("certificate"));
  out.iterations = r.value<int>("iterations");
  out.converged = r.value<bool>("converged");
  out.distinct_orientations = r.value<Eigen::Index>("distinct_orientations");
  if (r.find("robust")) out.robust = detail::robust_from(r.at("robust"), r.type() + " robust");
  if (r.find("bootstrap")) {
    const Reader b = r.child("bootstrap");
    payload::PayloadEstimate::Bootstrap boot;
    boot.replicates = b.value<int>("replicates");
    boot.failed = b.value<int>("failed");
    boot.seed = b.value<std::uint64_t>("seed");
    boot.level = b.number("level");
    payload_group_from(r.child("bootstrap_standard_errors"), boot, &payload::Interval::standard_errors);
    const Reader interval = r.child("interval");
    payload_group_from(interval.child("lower"), boot, &payload::Interval::lower);
    payload_group_from(interval.child("upper"), boot, &payload::Interval::upper);
    out.bootstrap = std::move(boot);
  }
  return out;
}

template <>
physical::RegressResult from_json<physical::RegressResult>(const std::string& text) {
  const Json document = detail::parse_object(text, "physical::RegressResult");
  const Reader r(document, "physical::RegressResult");
  physical::RegressResult out;
  out.status = r.status();
  out.warnings = r.warnings();
  if (!out.ok()) {
    out.message = r.error();
    return out;
  }
  out.bodies = r.value<int>("bodies");
  out.param_order = r.named("param_order", physical::parse_param_order);
  out.consistent_requested = r.value<bool>("consistent");
  out.prior_used = r.value<bool>("prior");
  out.samples = r.value<Eigen::Index>("samples");
  out.outputs = r.value<Eigen::Index>("outputs");
  out.rows = r.value<Eigen::Index>("rows");
  out.names = r.value<std::vector<std::string>>("names");
  out.parameters = r.vector("parameters");
  const Json& bodies = r.at("body");
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const Reader b(bodies[k], r.type() + " body[" + std::to_string(k) + "]");
    physical::RegressBody body;
    body.inertia.mass = b.number("mass");
    body.inertia.center_of_mass = b.vector3("center_of_mass");
    body.inertia.inertia = b.matrix3("inertia");
    const Eigen::VectorXd parameters = b.vector("parameters");
    if (parameters.size() != 10) throw std::invalid_argument(b.type() + " 'parameters': expected 10 numbers");
    body.parameters = parameters;
    body.pseudo_inertia_min_eig = b.number("pseudo_inertia_min_eig");
    body.physically_consistent = b.value<bool>("physically_consistent");
    body.determined = b.value<bool>("determined");
    out.body.push_back(body);
  }
  out.extra = r.vector("extra");
  out.identifiability.parameters = out.parameters.size();
  out.identifiability.rank = r.value<Eigen::Index>("rank");
  out.identifiability.condition = r.number("condition");
  const Json& base = r.at("base_parameters");
  out.identifiability.base.resize(static_cast<Eigen::Index>(base.size()), out.parameters.size());
  out.base_parameters.resize(static_cast<Eigen::Index>(base.size()));
  for (std::size_t i = 0; i < base.size(); ++i) {
    const Reader b(base[i], r.type() + " base_parameters[" + std::to_string(i) + "]");
    const Eigen::VectorXd row = b.vector("coefficients");
    if (row.size() != out.parameters.size()) {
      throw std::invalid_argument(b.type() + " 'coefficients': expected one per parameter");
    }
    out.identifiability.base.row(static_cast<Eigen::Index>(i)) = row.transpose();
    out.identifiability.base_names.push_back(b.value<std::string>("combination"));
    out.base_parameters(static_cast<Eigen::Index>(i)) = b.number("value");
  }
  out.identifiability.undetermined = undetermined_from(r);
  out.criterion = r.number("criterion");
  out.criterion_unconstrained = r.number("criterion_unconstrained");
  out.residual_rms = r.number("residual_rms");
  out.certificate = certificate_from(r.child("certificate"));
  out.iterations = r.value<int>("iterations");
  out.converged = r.value<bool>("converged");
  out.physically_consistent = r.value<bool>("physically_consistent");
  if (r.find("bootstrap")) {
    const Reader b = r.child("bootstrap");
    physical::RegressBootstrap boot;
    boot.replicates = b.value<int>("replicates");
    boot.failed = b.value<int>("failed");
    boot.seed = b.value<std::uint64_t>("seed");
    boot.level = b.number("level");
    const Reader p = b.child("parameters");
    boot.parameter_se = p.vector("standard_errors");
    boot.parameter_lower = p.vector("lower");
    boot.parameter_upper = p.vector("upper");
    const Reader q = b.child("base_parameters");
    boot.base_se = q.vector("standard_errors");
    boot.base_lower = q.vector("lower");
    boot.base_upper = q.vector("upper");
    out.bootstrap = std::move(boot);
  }
  return out;
}

template <>
hexapod::PhysicalEstimate from_json<hexapod::PhysicalEstimate>(const std::string& text) {
  const Json document = detail::parse_object(text, "hexapod::PhysicalEstimate");
  const Reader r(document, "hexapod::PhysicalEstimate");
  hexapod::PhysicalEstimate out;
  out.status = r.status();
  out.warnings = r.warnings();
  if (!out.ok()) {
    out.message = r.error();
    return out;
  }
  out.payload.mass = r.number("mass");
  out.payload.center_of_mass = r.vector3("center_of_mass");
  out.payload.inertia = r.matrix3("inertia");
  out.principal.moments = r.vector3("principal_moments");
  out.principal.axes = r.matrix3("principal_axes");
  out.strut_masses = r.named("strut_masses", hexapod::parse_strut_masses);
  out.strut_mass = r.at("strut_mass").is_array() ? r.vector("strut_mass") : Eigen::VectorXd::Constant(1, r.number("strut_mass"));
  const Eigen::MatrixXd M_p = r.matrix("M_p");
  if (M_p.rows() != 6 || M_p.cols() != 6) throw std::invalid_argument(r.type() + " 'M_p': expected a 6 x 6 matrix");
  out.M_p = M_p;
  const Eigen::VectorXd eigenvalues = r.vector("M_p_eigenvalues");
  if (eigenvalues.size() != 6) throw std::invalid_argument(r.type() + " 'M_p_eigenvalues': expected 6 numbers");
  out.M_p_eigenvalues = eigenvalues;
  if (r.find("modes_hz")) {
    const Eigen::VectorXd modes = r.vector("modes_hz");
    if (modes.size() != 6) throw std::invalid_argument(r.type() + " 'modes_hz': expected 6 numbers");
    out.modes_hz = hexapod::Vector6d(modes);
  }
  out.pseudo_inertia_min_eig = r.number("pseudo_inertia_min_eig");
  out.physically_consistent = r.value<bool>("physically_consistent");
  const Reader c = r.child("certificate");
  out.certificate = {c.number("stationarity"), c.number("primal_min_eig"), c.number("dual_min_eig"),
                     c.number("complementarity")};
  const Reader s = r.child("start_certificate");
  out.start_certificate = {s.number("primal_min_eig"), s.number("dual_min_eig"), s.number("complementarity"),
                           s.number("duality_gap")};
  out.criterion = r.number("criterion");
  out.criterion_kind = r.named("criterion_kind", hexapod::parse_physical_criterion);
  out.consistent_requested = r.value<bool>("consistent");
  out.iterations = r.value<int>("iterations");
  out.converged = r.value<bool>("converged");
  const Reader d = r.child("design");
  out.design.parameters = d.value<Eigen::Index>("parameters");
  out.design.rank = d.value<Eigen::Index>("rank");
  out.design.condition = d.number("condition");
  out.design.length_scale = d.number("length_scale");
  out.design.confounded = d.value<std::string>("confounded");
  out.m = r.value<Eigen::Index>("m");
  out.rank_a = r.value<Eigen::Index>("rank_a");
  const Reader offsets = r.child("offsets");
  const std::string mode = offsets.value<std::string>("mode");
  if (mode == "rest") {
    out.tare_a = offsets.vector("a");
    out.tare_b = offsets.vector("b");
  } else if (mode == "estimate") {
    out.offsets_c = offsets.vector("c");
  } else if (mode != "none") {
    throw std::invalid_argument(offsets.type() + ": unknown mode '" + mode + "'");
  }
  if (r.find("robust")) out.robust = detail::robust_from(r.at("robust"), r.type() + " robust");
  if (r.find("bootstrap")) {
    const Reader b = r.child("bootstrap");
    hexapod::PhysicalBootstrap boot;
    boot.replicates = b.value<int>("replicates");
    boot.failed = b.value<int>("failed");
    boot.seed = b.value<std::uint64_t>("seed");
    boot.M_p_eigenvalues = detail::spectrum_from(b.at("M_p_eigenvalues"), b.type() + " M_p_eigenvalues");
    if (b.find("modes_hz")) boot.modes_hz = detail::spectrum_from(b.at("modes_hz"), b.type() + " modes_hz");
    physical_group_from(r.child("standard_errors"), boot, &hexapod::EntryUncertainty::standard_errors);
    const Reader interval = r.child("interval");
    boot.level = interval.number("level");
    physical_group_from(interval.child("lower"), boot, &hexapod::EntryUncertainty::lower);
    physical_group_from(interval.child("upper"), boot, &hexapod::EntryUncertainty::upper);
    out.bootstrap = std::move(boot);
  }
  return out;
}

template <>
experiment::PhysicalExperimentResult from_json<experiment::PhysicalExperimentResult>(const std::string& text) {
  const Json document = detail::parse_object(text, "experiment::PhysicalExperimentResult");
  const Reader r(document, "experiment::PhysicalExperimentResult");
  if (r.value<std::string>("experiment") != "physical") {
    throw std::invalid_argument(r.type() + ": 'experiment' is not \"physical\"");
  }
  experiment::PhysicalExperimentResult out;
  hexapod::SimulationOptions& s = out.options.simulation;
  s.noise_var = r.number("noise_var");
  const double force_noise_var = r.number("force_noise_var");
  // to_json writes noise_var where no separate force noise was set: the same numbers either way.
  if (force_noise_var != s.noise_var) s.force_noise_var = force_noise_var;
  s.signal_var = r.number("signal_var");
  s.distribution = r.named("distribution", hexapod::parse_noise_distribution);
  out.trials = r.value<std::size_t>("trials");
  out.seed = r.value<std::uint64_t>("seed");
  if (r.find("payload")) {
    const Reader p = r.child("payload");
    out.options.payload = RigidBodyInertia{p.number("mass"), p.vector3("center_of_mass"), p.matrix3("inertia")};
  }
  out.truth = r.matrix("truth");
  out.options.methods.clear();
  out.options.variants.clear();
  const auto names = r.value<std::vector<std::string>>("methods");
  experiment::set_estimators(out.options, names);
  out.options.samples.clear();
  const Json& rows = r.at("rows");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Reader row(rows[i], r.type() + " rows[" + std::to_string(i) + "]");
    experiment::PhysicalExperimentRow result_row;
    result_row.samples = row.value<Eigen::Index>("samples");
    out.options.samples.push_back(result_row.samples);
    // Each row holds the estimators of "methods", in its order (the object's keys are unordered).
    const Reader methods = row.child("methods");
    for (const std::string& name : names) {
      const Reader m = methods.child(name.c_str());
      experiment::PhysicalMethodErrors errors;
      errors.name = name;
      errors.summary.mean = m.number("mean");
      errors.summary.std = m.number("std");
      errors.summary.median = m.number("median");
      errors.summary.max = m.number("max");
      errors.summary.min = m.number("min");
      errors.summary.count = m.value<std::size_t>("count");
      errors.summary.failures = m.value<std::size_t>("failures");
      errors.inconsistent = m.value<std::size_t>("inconsistent");
      result_row.methods.push_back(std::move(errors));
    }
    out.rows.push_back(std::move(result_row));
  }
  return out;
}

}  // namespace spdfit
