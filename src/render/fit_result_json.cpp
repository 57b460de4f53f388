// FitResult and its parts as JSON: the command line's fit contract (docs/cli.md) and the exact
// rendering of pickles.
#include "render/fit_result_json.hpp"

#include <array>
#include <stdexcept>

namespace spdfit::detail {

namespace {

// The noise model's source in the JSON of an estimate without one (NoiseModel's sources are
// "std", "cov" and "rest").
constexpr const char* kAssumedEqual = "assumed-equal";

// The names the JSON gives the enums, read back by name so that a reordering of the enumerators
// changes nothing.
Method method_from(const Json& object, const char* key, const std::string& type) {
  const auto name = value_from<std::string>(object, key, type);
  if (const auto method = parse_method(name)) return *method;
  throw std::invalid_argument(type + ": unknown method '" + name + "'");
}

Status status_from(const Json& object, const std::string& type) {
  const auto name = value_from<std::string>(object, "status", type);
  for (Status status : {Status::NotComputed, Status::Success, Status::NumericalFailure}) {
    if (name == to_string(status)) return status;
  }
  throw std::invalid_argument(type + ": unknown status '" + name + "'");
}

Json certificate_json(const PsdCertificate& c, JsonStyle style) {
  return {{"primal_min_eig", number_json(c.primal_min_eig, style)},
          {"dual_min_eig", number_json(c.dual_min_eig, style)},
          {"complementarity", number_json(c.complementarity, style)},
          {"duality_gap", number_json(c.duality_gap, style)}};
}

PsdCertificate certificate_from(const Json& object, const std::string& type) {
  const auto number = [&](const char* key) { return number_from(field(object, key, type), type + " '" + key + "'"); };
  return {number("primal_min_eig"), number("dual_min_eig"), number("complementarity"), number("duality_gap")};
}

// spd-tls's certificate on the boundary: the JSON's "certificate" too, told from psd-ls's by its keys.
Json boundary_certificate_json(const BoundaryCertificate& c, JsonStyle style) {
  return {{"rank", c.rank},
          {"stationarity", number_json(c.stationarity, style)},
          {"cross_block", number_json(c.cross_block, style)},
          {"multiplier_min_eig", number_json(c.multiplier_min_eig, style)}};
}

BoundaryCertificate boundary_certificate_from(const Json& object, const std::string& type) {
  const auto number = [&](const char* key) { return number_from(field(object, key, type), type + " '" + key + "'"); };
  BoundaryCertificate c;
  c.rank = value_from<Eigen::Index>(object, "rank", type);
  c.stationarity = number("stationarity");
  c.cross_block = number("cross_block");
  c.multiplier_min_eig = number("multiplier_min_eig");
  return c;
}

Json reason_json(const AutoReason& reason) { return {{"code", reason.code}, {"text", reason.text}}; }

AutoReason reason_from(const Json& object, const std::string& type) {
  return {value_from<std::string>(object, "code", type), value_from<std::string>(object, "text", type)};
}

Json interval_json(const Interval& interval, JsonStyle style) {
  return {{"level", interval.level},
          {"type", to_string(interval.type)},
          {"lower", matrix_json(interval.lower, style)},
          {"upper", matrix_json(interval.upper, style)}};
}

Interval interval_from(const Json& object, const std::string& type) {
  Interval out;
  out.level = number_from(field(object, "level", type), type + " 'level'");
  if (optional_field(object, "type")) {  // absent in results written before the interval types
    const auto name = value_from<std::string>(object, "type", type);
    const std::optional<BootstrapInterval> kind = bootstrap_interval_named(name);
    if (!kind) throw std::invalid_argument(type + " 'type': expected percentile, basic or normal, got '" + name + "'");
    out.type = *kind;
  }
  out.lower = matrix_from(field(object, "lower", type), type + " 'lower'");
  out.upper = matrix_from(field(object, "upper", type), type + " 'upper'");
  return out;
}

// The diagnostics object of the fit contract; m, n and d are the result's (top level).
Json diagnostics_json(const Diagnostics& d, JsonStyle style) {
  Json out;
  out["rank_a"] = d.rank_a;
  out["rank_b"] = d.rank_b;
  out["cond_a"] = number_json(d.cond_a, style);
  out["cond_b"] = number_json(d.cond_b, style);
  out["cond_a_scaled"] = number_json(d.cond_a_scaled, style);
  out["cond_b_scaled"] = number_json(d.cond_b_scaled, style);
  out["rank_decided_on"] = "column-scaled";
  out["singular_values_a"] = vector_json(d.singular_values_a, style);
  out["singular_values_b"] = vector_json(d.singular_values_b, style);
  out["residual_norm"] = number_json(d.residual_norm, style);
  out["symmetric"] = d.symmetric;
  out["positive_definite"] = d.positive_definite;
  out["positive_semidefinite"] = d.positive_semidefinite;
  put_optional(out, "min_eigenvalue", d.min_eigenvalue, style);
  put_optional(out, "max_eigenvalue", d.max_eigenvalue, style);
  put_optional(out, "area_criterion", d.area_criterion, style);
  put_optional(out, "area_criterion_minimum", d.area_criterion_minimum, style);
  if (d.cross_term_positive_definite) out["cross_term_positive_definite"] = *d.cross_term_positive_definite;
  put_optional(out, "tls_sigma_n", d.tls_sigma_n, style);
  put_optional(out, "tls_sigma_n1", d.tls_sigma_n1, style);
  put_optional(out, "tls_correction_norm", d.tls_correction_norm, style);
  put_optional(out, "tls_v22_min_singular_value", d.tls_v22_min_singular_value, style);
  put_optional(out, "noise_sigma", d.noise_sigma, style);
  if (d.iterations) out["iterations"] = *d.iterations;
  put_optional(out, "gradient_norm", d.gradient_norm, style);
  if (d.converged) out["converged"] = *d.converged;
  if (d.certificate) out["certificate"] = certificate_json(*d.certificate, style);
  if (d.boundary_certificate) out["certificate"] = boundary_certificate_json(*d.boundary_certificate, style);
  // Without a model the estimate assumed equal noise in every column of A and B: said so.
  out["noise_model"] = d.noise_model ? noise_model_json(*d.noise_model, style) : Json{{"source", kAssumedEqual}};
  if (d.chosen_method) out["chosen_method"] = std::string(to_string(*d.chosen_method));
  if (d.reason) out["reason"] = reason_json(*d.reason);
  return out;
}

// The diagnostics object; m, n and d from `shape`, the object that holds them.
Diagnostics diagnostics_from(const Json& object, const Json& shape, const std::string& type) {
  const std::string what = type + " diagnostics";
  const auto number = [&](const char* key) { return number_from(field(object, key, what), what + " '" + key + "'"); };
  const auto optional = [&](const char* key) { return optional_number_from(object, key, what); };
  Diagnostics d;
  d.m = value_from<Eigen::Index>(shape, "m", type);
  d.n = value_from<Eigen::Index>(shape, "n", type);
  d.d = value_from<Eigen::Index>(shape, "d", type);
  d.rank_a = value_from<Eigen::Index>(object, "rank_a", what);
  d.rank_b = value_from<Eigen::Index>(object, "rank_b", what);
  d.cond_a = number("cond_a");
  d.cond_b = number("cond_b");
  d.cond_a_scaled = number("cond_a_scaled");
  d.cond_b_scaled = number("cond_b_scaled");
  d.singular_values_a = vector_from(field(object, "singular_values_a", what), what + " 'singular_values_a'");
  d.singular_values_b = vector_from(field(object, "singular_values_b", what), what + " 'singular_values_b'");
  d.residual_norm = number("residual_norm");
  d.symmetric = value_from<bool>(object, "symmetric", what);
  d.positive_definite = value_from<bool>(object, "positive_definite", what);
  d.positive_semidefinite = value_from<bool>(object, "positive_semidefinite", what);
  d.min_eigenvalue = optional("min_eigenvalue");
  d.max_eigenvalue = optional("max_eigenvalue");
  d.area_criterion = optional("area_criterion");
  d.area_criterion_minimum = optional("area_criterion_minimum");
  if (optional_field(object, "cross_term_positive_definite")) {
    d.cross_term_positive_definite = value_from<bool>(object, "cross_term_positive_definite", what);
  }
  d.tls_sigma_n = optional("tls_sigma_n");
  d.tls_sigma_n1 = optional("tls_sigma_n1");
  d.tls_correction_norm = optional("tls_correction_norm");
  d.tls_v22_min_singular_value = optional("tls_v22_min_singular_value");
  d.noise_sigma = optional("noise_sigma");
  if (optional_field(object, "iterations")) d.iterations = value_from<int>(object, "iterations", what);
  d.gradient_norm = optional("gradient_norm");
  if (optional_field(object, "converged")) d.converged = value_from<bool>(object, "converged", what);
  if (const Json* c = optional_field(object, "certificate")) {
    if (optional_field(*c, "stationarity")) {
      d.boundary_certificate = boundary_certificate_from(*c, what + " certificate");
    } else {
      d.certificate = certificate_from(*c, what + " certificate");
    }
  }
  if (const Json* m = optional_field(object, "noise_model")) {
    const Json* source = optional_field(*m, "source");
    if (!(source && source->is_string() && source->get<std::string>() == kAssumedEqual)) {
      d.noise_model = noise_model_from(*m, what + " noise_model");
    }
  }
  if (optional_field(object, "chosen_method")) d.chosen_method = method_from(object, "chosen_method", what);
  if (const Json* r = optional_field(object, "reason")) d.reason = reason_from(*r, what + " reason");
  return d;
}

// The bootstrap's own fields (the "bootstrap" object of the fit contract); Exact also writes
// group_rows and groups for the multinomial scheme (0 there).
Json bootstrap_details_json(const Bootstrap& b, JsonStyle style) {
  Json out = {{"replicates", b.replicates}, {"failed", b.failed},     {"seed", b.seed},
              {"method", to_string(b.method)}, {"scheme", b.scheme}};
  if (b.scheme == "poisson_groups" || style == JsonStyle::Exact) {
    out["group_rows"] = b.group_rows;
    out["groups"] = b.groups;
  }
  if (b.eigenvalues) out["eigenvalues"] = spectrum_json(*b.eigenvalues, style);
  return out;
}

// `details` as bootstrap_details_json wrote it, `estimates` the object with standard_errors,
// interval and bias (the result in the fit contract, the same object for a Bootstrap alone);
// `what` names it in errors.
Bootstrap bootstrap_from(const Json& details, const Json& estimates, const std::string& what) {
  Bootstrap b;
  b.replicates = value_from<int>(details, "replicates", what);
  b.failed = value_from<int>(details, "failed", what);
  b.seed = value_from<std::uint64_t>(details, "seed", what);
  b.method = method_from(details, "method", what);
  b.scheme = value_from<std::string>(details, "scheme", what);
  if (optional_field(details, "group_rows")) b.group_rows = value_from<Eigen::Index>(details, "group_rows", what);
  if (optional_field(details, "groups")) b.groups = value_from<Eigen::Index>(details, "groups", what);
  if (const Json* e = optional_field(details, "eigenvalues")) b.eigenvalues = spectrum_from(*e, what + " eigenvalues");
  b.standard_errors = matrix_from(field(estimates, "standard_errors", what), what + " 'standard_errors'");
  b.bias = matrix_from(field(estimates, "bias", what), what + " 'bias'");
  b.interval = interval_from(field(estimates, "interval", what), what + " interval");
  return b;
}

Json bootstrap_json(const Bootstrap& b, JsonStyle style) {
  Json out = bootstrap_details_json(b, style);
  out["standard_errors"] = matrix_json(b.standard_errors, style);
  out["interval"] = interval_json(b.interval, style);
  out["bias"] = matrix_json(b.bias, style);
  return out;
}

}  // namespace

Json spectrum_json(const SpectrumUncertainty& s, JsonStyle style) {
  Json clusters = Json::array();
  for (const std::vector<Eigen::Index>& c : s.clusters) clusters.push_back(c);
  return {{"estimate", vector_json(s.estimate, style)}, {"standard_errors", vector_json(s.standard_errors, style)},
          {"lower", vector_json(s.lower, style)},       {"upper", vector_json(s.upper, style)},
          {"clusters", clusters},                       {"failed", s.failed}};
}

RobustReport robust_from(const Json& o, const std::string& what) {
  RobustReport report;
  const std::string loss = value_from<std::string>(o, "method", what);
  const std::optional<RobustLoss> named = robust_loss_named(loss);
  if (!named) throw std::invalid_argument(what + ": unknown method '" + loss + "'");
  report.method = *named;
  report.tuning = number_from(field(o, "tuning", what), what + " 'tuning'");
  report.scale = number_from(field(o, "scale", what), what + " 'scale'");
  report.rows_downweighted = value_from<std::vector<std::uint64_t>>(o, "rows_downweighted", what);
  report.rows_downweighted_count = value_from<std::uint64_t>(o, "rows_downweighted_count", what);
  report.weights_min = number_from(field(o, "weights_min", what), what + " 'weights_min'");
  report.iterations = value_from<int>(o, "iterations", what);
  report.converged = value_from<bool>(o, "converged", what);
  return report;
}

SpectrumUncertainty spectrum_from(const Json& object, const std::string& type) {
  const auto vector = [&](const char* key) { return vector_from(field(object, key, type), type + " '" + key + "'"); };
  SpectrumUncertainty s;
  s.estimate = vector("estimate");
  s.standard_errors = vector("standard_errors");
  s.lower = vector("lower");
  s.upper = vector("upper");
  s.clusters = value_from<std::vector<std::vector<Eigen::Index>>>(object, "clusters", type);
  s.failed = value_from<int>(object, "failed", type);
  return s;
}

Json robust_json(const RobustReport& r, JsonStyle style) {
  return Json{{"method", to_string(r.method)},
              {"tuning", number_json(r.tuning, style)},
              {"scale", number_json(r.scale, style)},
              {"rows_downweighted", r.rows_downweighted},
              {"rows_downweighted_count", r.rows_downweighted_count},
              {"weights_min", number_json(r.weights_min, style)},
              {"iterations", r.iterations},
              {"converged", r.converged}};
}

Json fit_result_json(const FitResult& result, JsonStyle style) {
  Json out;
  out["method"] = std::string(to_string(result.method));
  out["status"] = to_string(result.status);
  out["m"] = result.diagnostics.m;
  out["n"] = result.diagnostics.n;
  out["d"] = result.diagnostics.d;
  out["X"] = matrix_json(result.X, style);
  if (!result.row_names.empty()) out["row_names"] = result.row_names;
  if (!result.column_names.empty()) out["column_names"] = result.column_names;
  if (!result.a_columns.empty()) {
    out["a_columns"] = result.a_columns;
    out["b_columns"] = result.b_columns;
  }
  if (const auto& o = result.offsets) {
    Json offsets{{"mode", to_string(o->mode)}};
    if (o->mode == Offsets::Estimate) offsets["c"] = vector_json(o->c, style);
    if (o->mode == Offsets::Rest) {
      offsets["a"] = vector_json(o->a, style);
      offsets["b"] = vector_json(o->b, style);
    }
    out["offsets"] = std::move(offsets);
  }
  if (const auto& r = result.robust) out["robust"] = robust_json(*r, style);
  out["diagnostics"] = diagnostics_json(result.diagnostics, style);
  put_warnings(out, result.warnings);
  // Exact keeps a message that a successful result should not have, too.
  if (!result.ok() || (style == JsonStyle::Exact && !result.message.empty())) out["error"] = result.message;
  if (const auto& b = result.bootstrap) {
    out["standard_errors"] = matrix_json(b->standard_errors, style);
    out["interval"] = interval_json(b->interval, style);
    out["bias"] = matrix_json(b->bias, style);
    out["bootstrap"] = bootstrap_details_json(*b, style);
  }
  return out;
}

FitResult fit_result_from(const Json& object, const std::string& type) {
  FitResult r;
  r.method = method_from(object, "method", type);
  r.status = status_from(object, type);
  r.X = matrix_from(field(object, "X", type), type + " 'X'");
  r.diagnostics = diagnostics_from(field(object, "diagnostics", type), object, type);
  if (optional_field(object, "row_names")) r.row_names = value_from<std::vector<std::string>>(object, "row_names", type);
  if (optional_field(object, "column_names")) {
    r.column_names = value_from<std::vector<std::string>>(object, "column_names", type);
  }
  if (optional_field(object, "a_columns")) {
    r.a_columns = value_from<std::string>(object, "a_columns", type);
    r.b_columns = value_from<std::string>(object, "b_columns", type);
  }
  if (const Json* o = optional_field(object, "offsets")) {
    FitOffsets offsets;
    const std::string mode = value_from<std::string>(*o, "mode", type + " offsets");
    const std::optional<Offsets> named = offsets_named(mode);
    if (!named) throw std::invalid_argument(type + ": 'offsets' has an unknown mode '" + mode + "'");
    offsets.mode = *named;
    if (optional_field(*o, "c")) offsets.c = vector_from(field(*o, "c", type), type + " offsets 'c'");
    if (optional_field(*o, "a")) offsets.a = vector_from(field(*o, "a", type), type + " offsets 'a'");
    if (optional_field(*o, "b")) offsets.b = vector_from(field(*o, "b", type), type + " offsets 'b'");
    r.offsets = std::move(offsets);
  }
  if (const Json* o = optional_field(object, "robust")) r.robust = robust_from(*o, type + " robust");
  r.warnings = warnings_from(object, type);
  if (optional_field(object, "error")) r.message = value_from<std::string>(object, "error", type);
  // (A hexapod identification's entry may hold only the modes' intervals there.)
  const Json* details = optional_field(object, "bootstrap");
  if (details && details->contains("replicates")) r.bootstrap = bootstrap_from(*details, object, type + " bootstrap");
  return r;
}

}  // namespace spdfit::detail

namespace spdfit {

using detail::dump;
using detail::Json;

std::string to_json(const FitResult& result, JsonStyle style) { return dump(detail::fit_result_json(result, style), style); }

std::string to_json(const Diagnostics& diagnostics, JsonStyle style) {
  Json out = detail::diagnostics_json(diagnostics, style);
  out["m"] = diagnostics.m;
  out["n"] = diagnostics.n;
  out["d"] = diagnostics.d;
  return dump(out, style);
}

std::string to_json(const PsdCertificate& certificate, JsonStyle style) {
  return dump(detail::certificate_json(certificate, style), style);
}

std::string to_json(const BoundaryCertificate& certificate, JsonStyle style) {
  return dump(detail::boundary_certificate_json(certificate, style), style);
}

std::string to_json(const AutoReason& reason, JsonStyle style) { return dump(detail::reason_json(reason), style); }

std::string to_json(const Interval& interval, JsonStyle style) {
  return dump(detail::interval_json(interval, style), style);
}

std::string to_json(const SpectrumUncertainty& spectrum, JsonStyle style) {
  return dump(detail::spectrum_json(spectrum, style), style);
}

std::string to_json(const Bootstrap& bootstrap, JsonStyle style) {
  return dump(detail::bootstrap_json(bootstrap, style), style);
}

template <>
FitResult from_json<FitResult>(const std::string& text) {
  return detail::fit_result_from(detail::parse_object(text, "FitResult"), "FitResult");
}

template <>
Diagnostics from_json<Diagnostics>(const std::string& text) {
  const Json object = detail::parse_object(text, "Diagnostics");
  return detail::diagnostics_from(object, object, "Diagnostics");
}

template <>
PsdCertificate from_json<PsdCertificate>(const std::string& text) {
  return detail::certificate_from(detail::parse_object(text, "PsdCertificate"), "PsdCertificate");
}

template <>
BoundaryCertificate from_json<BoundaryCertificate>(const std::string& text) {
  return detail::boundary_certificate_from(detail::parse_object(text, "BoundaryCertificate"), "BoundaryCertificate");
}

template <>
AutoReason from_json<AutoReason>(const std::string& text) {
  return detail::reason_from(detail::parse_object(text, "AutoReason"), "AutoReason");
}

template <>
Interval from_json<Interval>(const std::string& text) {
  return detail::interval_from(detail::parse_object(text, "Interval"), "Interval");
}

template <>
SpectrumUncertainty from_json<SpectrumUncertainty>(const std::string& text) {
  return detail::spectrum_from(detail::parse_object(text, "SpectrumUncertainty"), "SpectrumUncertainty");
}

template <>
Bootstrap from_json<Bootstrap>(const std::string& text) {
  const Json object = detail::parse_object(text, "Bootstrap");
  return detail::bootstrap_from(object, object, "Bootstrap");
}

}  // namespace spdfit
