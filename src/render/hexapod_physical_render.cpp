// The physical estimate in `spdfit hexapod identify --physical`: its JSON object (the "physical"
// object of `hexapod identify --json`, and Python's spdfit.physical.PhysicalEstimate) and its report
// for people, each parameter beside the geometry's nominal (CAD) value.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "render/fit_result_json.hpp"
#include "render/json_values.hpp"
#include "render/text_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/render.hpp"

namespace spdfit::hexapod {

namespace {

using json = spdfit::detail::OrderedJson;
using spdfit::detail::matrix_json;
using spdfit::detail::number_json;
using spdfit::detail::vector_json;

// A strut-mass value: one number for a common mass, else the list.
json struts(const Eigen::MatrixXd& values, StrutMasses kind) {
  return kind == StrutMasses::Common && values.size() == 1 ? number_json(values(0, 0)) : vector_json(values.reshaped());
}

json spectrum(const SpectrumUncertainty& s) {
  json clusters = json::array();
  for (const std::vector<Eigen::Index>& c : s.clusters) clusters.push_back(c);
  return {{"estimate", vector_json(s.estimate)}, {"standard_errors", vector_json(s.standard_errors)},
          {"lower", vector_json(s.lower)},       {"upper", vector_json(s.upper)},
          {"clusters", clusters},           {"failed", s.failed}};
}

// The keys with bootstrap uncertainty, each from one member of EntryUncertainty.
json entries(const PhysicalBootstrap& b, Eigen::MatrixXd EntryUncertainty::*member, StrutMasses kind) {
  return {{"mass", number_json((b.mass.*member)(0, 0))},
          {"center_of_mass", vector_json(b.center_of_mass.*member)},
          {"inertia", matrix_json(b.inertia.*member)},
          {"principal_moments", vector_json(b.principal_moments.*member)},
          {"strut_mass", struts(b.strut_mass.*member, kind)},
          {"M_p", matrix_json(b.M_p.*member)}};
}

json physical_object(const PhysicalEstimate& e) {
  json out;
  out["status"] = to_string(e.status);
  if (!e.ok()) {
    out["error"] = e.message;
    spdfit::detail::put_warnings(out, e.warnings);
    return out;
  }
  out["mass"] = number_json(e.payload.mass);
  out["center_of_mass"] = vector_json(e.payload.center_of_mass);
  out["inertia"] = matrix_json(e.payload.inertia);
  out["principal_moments"] = vector_json(e.principal.moments);
  out["principal_axes"] = matrix_json(e.principal.axes);
  out["strut_mass"] = struts(e.strut_mass, e.strut_masses);
  out["strut_masses"] = std::string(to_string(e.strut_masses));
  out["M_p"] = matrix_json(e.M_p);
  out["M_p_eigenvalues"] = vector_json(e.M_p_eigenvalues);
  if (e.modes_hz) out["modes_hz"] = vector_json(*e.modes_hz);
  out["pseudo_inertia_min_eig"] = number_json(e.pseudo_inertia_min_eig);
  out["physically_consistent"] = e.physically_consistent;
  out["certificate"] = {{"stationarity", number_json(e.certificate.stationarity)},
                        {"primal_min_eig", number_json(e.certificate.primal_min_eig)},
                        {"dual_min_eig", number_json(e.certificate.dual_min_eig)},
                        {"complementarity", number_json(e.certificate.complementarity)}};
  out["start_certificate"] = {{"primal_min_eig", number_json(e.start_certificate.primal_min_eig)},
                              {"dual_min_eig", number_json(e.start_certificate.dual_min_eig)},
                              {"complementarity", number_json(e.start_certificate.complementarity)},
                              {"duality_gap", number_json(e.start_certificate.duality_gap)}};
  out["criterion"] = number_json(e.criterion);
  out["criterion_kind"] = std::string(to_string(e.criterion_kind));
  out["consistent"] = e.consistent_requested;
  out["iterations"] = e.iterations;
  out["converged"] = e.converged;
  out["design"] = {{"parameters", e.design.parameters},
                   {"rank", e.design.rank},
                   {"condition", number_json(e.design.condition)},
                   {"length_scale", number_json(e.design.length_scale)},
                   {"confounded", e.design.confounded}};
  out["m"] = e.m;
  out["rank_a"] = e.rank_a;
  out["offsets"] = e.tare_b.size()      ? json{{"mode", "rest"}, {"a", vector_json(e.tare_a)}, {"b", vector_json(e.tare_b)}}
                   : e.offsets_c.size() ? json{{"mode", "estimate"}, {"c", vector_json(e.offsets_c)}}
                                        : json{{"mode", "none"}};
  // The robust report as the fit's (render/fit_result_json.cpp), in this document's key order.
  if (e.robust) out["robust"] = json(spdfit::detail::robust_json(*e.robust, spdfit::JsonStyle::Contract));
  spdfit::detail::put_warnings(out, e.warnings);
  if (const auto& b = e.bootstrap) {
    out["standard_errors"] = entries(*b, &EntryUncertainty::standard_errors, e.strut_masses);
    out["interval"] = {{"level", b->level},
                       {"lower", entries(*b, &EntryUncertainty::lower, e.strut_masses)},
                       {"upper", entries(*b, &EntryUncertainty::upper, e.strut_masses)}};
    json boot = {{"replicates", b->replicates}, {"failed", b->failed}, {"seed", b->seed},
                 {"M_p_eigenvalues", spectrum(b->M_p_eigenvalues)}};
    if (b->modes_hz) boot["modes_hz"] = spectrum(*b->modes_hz);
    out["bootstrap"] = std::move(boot);
  }
  return out;
}

// The truth, when options give a 6 x 6 one.
const Eigen::MatrixXd* truth_of(const IdentifyOptions& options) {
  if (!options.truth || options.truth->rows() != 6 || options.truth->cols() != 6) return nullptr;
  return &*options.truth;
}

// One row of the parameter table: the name, the estimate, the nominal value ("-" for none) and,
// with a bootstrap, the standard error and the interval.
struct Row {
  std::string name;
  double estimate = 0.0;
  std::optional<double> nominal;
  std::optional<double> se, lower, upper;
};

// With a bootstrap, the estimate and its interval to the standard error's third significant
// digit (interval_decimals), so that whether a value lies inside can be read.
std::string row_text(const Row& r, bool bootstrap) {
  char line[256];
  const bool interval = bootstrap && r.se;
  const int decimals = interval ? interval_decimals(*r.se) : 0;
  const std::string estimate =
      interval ? format_fixed(r.estimate, decimals) : format_number(r.estimate, Precision::Full);
  std::snprintf(line, sizeof line, "  %-28s %12s %12s", r.name.c_str(), estimate.c_str(),
                r.nominal ? format_number(*r.nominal, Precision::Full).c_str() : "-");
  std::string out = line;
  if (interval) {
    std::snprintf(line, sizeof line, " %11s   [%s, %s]", format_fixed(*r.se, decimals).c_str(),
                  format_fixed(*r.lower, decimals).c_str(), format_fixed(*r.upper, decimals).c_str());
    out += line;
  }
  return out + "\n";
}

// The rows of a group of values (mass, centre of mass, ...) with their bootstrap entries.
void add_rows(std::vector<Row>& rows, const std::vector<std::string>& names, const Eigen::MatrixXd& estimate,
              const std::optional<Eigen::MatrixXd>& nominal, const EntryUncertainty* uncertainty,
              const std::vector<std::pair<int, int>>& entries) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto [i, j] = entries[k];
    Row r{names[k], estimate(i, j), std::nullopt, std::nullopt, std::nullopt, std::nullopt};
    if (nominal) r.nominal = (*nominal)(i, j);
    if (uncertainty && uncertainty->standard_errors.rows() > i && uncertainty->standard_errors.cols() > j) {
      r.se = uncertainty->standard_errors(i, j);
      r.lower = uncertainty->lower(i, j);
      r.upper = uncertainty->upper(i, j);
    }
    rows.push_back(r);
  }
}

}  // namespace

std::string physical_json(const PhysicalEstimate& estimate) { return physical_object(estimate).dump(2) + "\n"; }

std::string to_json(const PhysicalEstimate& estimate, const IdentifyOptions& options) {
  json out = physical_object(estimate);
  if (const Eigen::MatrixXd* truth = truth_of(options); truth && estimate.ok()) {
    const double error = (estimate.M_p - *truth).norm();
    out["error_vs_truth"] = number_json(error);
  }
  return out.dump(2) + "\n";
}

std::string report(const PhysicalEstimate& e, const Geometry& geometry, const IdentifyOptions& options) {
  std::ostringstream out;
  const std::string criterion =
      e.criterion_kind == PhysicalCriterion::ErrorsInVariables ? "errors in variables" : "least squares";
  out << "Physical estimate (" << criterion << ", "
      << (e.consistent_requested ? "physically consistent" : "unconstrained") << "; strut masses "
      << (e.strut_masses == StrutMasses::Geometry ? std::string("from the geometry")
                                                  : "estimated, " + std::string(to_string(e.strut_masses)))
      << ")\n";
  if (!e.ok()) {
    out << "  failed: " << e.message << "\n";
    return out.str();
  }
  const PhysicalBootstrap* b = e.bootstrap ? &*e.bootstrap : nullptr;
  const bool boot = b != nullptr;
  char line[256];
  std::snprintf(line, sizeof line, "  %-28s %12s %12s", "parameter ({P} axes, SI)", "estimate", "nominal");
  out << line;
  if (boot) {
    std::snprintf(line, sizeof line, " %11s   [%s interval]", "std error",
                  format_percent(b->level, Precision::Medium).c_str());
    out << line;
  }
  out << "\n";

  std::vector<Row> rows;
  add_rows(rows, {"mass (kg)"}, Eigen::MatrixXd::Constant(1, 1, e.payload.mass),
           Eigen::MatrixXd::Constant(1, 1, geometry.payload_mass), boot ? &b->mass : nullptr, {{0, 0}});
  add_rows(rows, {"centre of mass x (m)", "centre of mass y (m)", "centre of mass z (m)"},
           e.payload.center_of_mass, Eigen::MatrixXd(Eigen::Vector3d::Zero()),
           boot ? &b->center_of_mass : nullptr, {{0, 0}, {1, 0}, {2, 0}});
  add_rows(rows,
           {"inertia xx (kg m^2)", "inertia yy (kg m^2)", "inertia zz (kg m^2)", "inertia xy (kg m^2)",
            "inertia xz (kg m^2)", "inertia yz (kg m^2)"},
           e.payload.inertia, Eigen::MatrixXd(geometry.payload_inertia), boot ? &b->inertia : nullptr,
           {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}});
  const PrincipalInertia nominal_principal = principal_inertia(geometry.payload_inertia);
  add_rows(rows,
           {"principal moment 1 (kg m^2)", "principal moment 2 (kg m^2)", "principal moment 3 (kg m^2)"},
           e.principal.moments, Eigen::MatrixXd(nominal_principal.moments),
           boot ? &b->principal_moments : nullptr, {{0, 0}, {1, 0}, {2, 0}});
  if (e.strut_masses == StrutMasses::Common) {
    add_rows(rows, {"strut mass, common (kg)"}, e.strut_mass,
             Eigen::MatrixXd::Constant(1, 1, geometry.strut_mass.mean()), boot ? &b->strut_mass : nullptr,
             {{0, 0}});
  } else if (e.strut_masses == StrutMasses::Each) {
    std::vector<std::string> names;
    std::vector<std::pair<int, int>> entries;
    for (int i = 0; i < 6; ++i) {
      names.push_back("strut mass " + std::to_string(i + 1) + " (kg)");
      entries.emplace_back(i, 0);
    }
    add_rows(rows, names, e.strut_mass, Eigen::MatrixXd(geometry.strut_mass), boot ? &b->strut_mass : nullptr,
             entries);
  }
  for (const Row& r : rows) out << row_text(r, boot);
  if (e.strut_masses == StrutMasses::Geometry) {
    out << "  strut masses (kg), from the geometry, not estimated: " << spdfit::detail::fixed_values(geometry.strut_mass, 4)
        << "\n";
  }
  out << "  principal axes (columns)\n";
  for (int i = 0; i < 3; ++i) {
    std::snprintf(line, sizeof line, "    %9.5f %9.5f %9.5f\n", e.principal.axes(i, 0),
                  e.principal.axes(i, 1), e.principal.axes(i, 2));
    out << line;
  }

  const Eigen::MatrixXd* truth = truth_of(options);
  std::vector<std::string> titles{"M_p(theta)"};
  std::vector<Eigen::MatrixXd> matrices{Eigen::MatrixXd(e.M_p)};
  if (truth) {
    titles.insert(titles.begin(), "truth");
    matrices.insert(matrices.begin(), *truth);
  }
  out << "\n" << format_side_by_side(titles, matrices);
  if (truth) out << "error ||M_p(theta) - truth||_F = " << format_fixed((e.M_p - *truth).norm()) << "\n";
  if (boot) {
    out << "eigenvalues (kg), " << b->replicates << " bootstrap resamples (" << b->failed << " failed, seed "
        << b->seed << "): value +- standard error   [interval]\n"
        << report(b->M_p_eigenvalues, "  ");
    if (b->modes_hz) out << "modes (Hz)\n" << report(*b->modes_hz, "  ");
  } else {
    out << "eigenvalues (kg)   " << spdfit::detail::fixed_values(e.M_p_eigenvalues, 4) << "\n";
    if (e.modes_hz) out << "modes (Hz)         " << spdfit::detail::fixed_values(*e.modes_hz, 2) << "\n";
  }
  out << "pseudo-inertia min eig " << format_number(e.pseudo_inertia_min_eig) << " kg ("
      << (e.physically_consistent ? "physically consistent" : "NOT physically consistent") << ")\n"
      << "criterion " << format_number(e.criterion, Precision::Full) << ", " << e.iterations
      << " Newton steps, " << (e.converged ? "converged" : "NOT converged")
      << "; KKT certificate: stationarity " << format_number(e.certificate.stationarity)
      << ", primal min eig " << format_number(e.certificate.primal_min_eig) << ", dual min eig "
      << format_number(e.certificate.dual_min_eig) << ", complementarity "
      << format_number(e.certificate.complementarity) << "\n"
      << "design: rank " << e.design.rank << " of " << e.design.parameters << " parameters, condition "
      << format_number(e.design.condition) << "\n";
  if (e.robust) out << spdfit::detail::robust_line(*e.robust);
  if (e.offsets_c.size()) {
    out << "offsets: estimated with the payload (B ~= A M_p + 1 c^T), c = [" << format_numbers(e.offsets_c, Precision::Full)
        << "] N\n";
  } else if (e.tare_b.size()) {
    out << "offsets: the rest rows' means subtracted, A [" << format_numbers(e.tare_a, Precision::Full) << "], B ["
        << format_numbers(e.tare_b, Precision::Full) << "]\n";
  }
  for (const Warning& w : e.warnings) out << "warning: " << w.text << "\n";
  return out.str();
}

}  // namespace spdfit::hexapod
