// The physical estimate in `spdfit hexapod identify --physical`: its JSON object and its report
// for people, each parameter beside the geometry's nominal (CAD) value.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "render/fit_result_json.hpp"
#include "render/text_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/render.hpp"

namespace spdfit::hexapod {

namespace {

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

std::string to_json(const PhysicalEstimate& estimate, const IdentifyOptions& options) {
  nlohmann::ordered_json out = nlohmann::ordered_json::parse(physical_json(estimate));
  if (const Eigen::MatrixXd* truth = truth_of(options); truth && estimate.ok()) {
    const double error = (estimate.M_p - *truth).norm();
    out["error_vs_truth"] =
        std::isfinite(error) ? nlohmann::ordered_json(error) : nlohmann::ordered_json(nullptr);
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
