// The bootstrap of physical identification: every key of the estimate, entry by entry, over
// multinomial resamples of the rows (the fit's own bootstrap machinery: resample_rows, the
// replicate generators keyed by (seed, r), parallel_for, summarize_spectrum).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "hexapod/physical_fit.hpp"
#include "numerics/parallel.hpp"
#include "spdfit/hexapod/model.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit::hexapod::detail {

namespace {

// One replicate's values, flattened in the order of the groups below; empty when it failed.
using Values = std::vector<double>;

struct Group {
  Eigen::Index rows, cols;
  EntryUncertainty PhysicalBootstrap::*member;
};

// The q-quantile of sorted values, interpolating between order statistics (numpy.quantile's
// default, as the fit's bootstrap intervals).
double quantile(const std::vector<double>& sorted, double q) {
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

void flatten(const PhysicalEstimate& e, Values& out) {
  out.push_back(e.payload.mass);
  for (int i = 0; i < 3; ++i) out.push_back(e.payload.center_of_mass(i));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) out.push_back(e.payload.inertia(i, j));
  for (int i = 0; i < 3; ++i) out.push_back(e.principal.moments(i));
  for (Eigen::Index i = 0; i < e.strut_mass.size(); ++i) out.push_back(e.strut_mass(i));
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) out.push_back(e.M_p(i, j));
}

}  // namespace

PhysicalOptions replicate_options(PhysicalOptions options) {
  options.bootstrap = 0;
  options.plausibility_check = false;  // a resample is judged by the intervals, not refused
  return options;
}

void bootstrap_physical(PhysicalEstimate& estimate, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                        const PhysicalModel& model, const Geometry& geometry, const PhysicalOptions& options) {
  const PhysicalOptions quiet = replicate_options(options);
  bootstrap_physical(estimate, geometry, options, [&](std::size_t r) -> std::optional<PhysicalEstimate> {
    const TriangularFactor factor = spdfit::detail::resample_rows(A, B, options.seed, r, options.intercept);
    return fit_physical(factor, model, geometry, quiet, false);
  });
}

void bootstrap_physical(PhysicalEstimate& estimate, const Geometry& geometry, const PhysicalOptions& options,
                        const PhysicalReplicate& replicate) {
  const auto replicates = static_cast<std::size_t>(options.bootstrap);
  std::vector<Values> values(replicates);
  std::vector<std::optional<Eigen::VectorXd>> eigenvalues(replicates), modes(replicates);
  const bool with_modes = estimate.modes_hz.has_value();
  const Eigen::MatrixXd stiffness = geometry.strut_stiffness.asDiagonal();
  spdfit::detail::parallel_for(replicates, options.threads, [&](std::size_t r) {
    try {
      const std::optional<PhysicalEstimate> fitted = replicate(r);
      if (!fitted || !fitted->ok()) return;
      const PhysicalEstimate& e = *fitted;
      Values v;
      flatten(e, v);
      if (!std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); })) return;
      values[r] = std::move(v);
      eigenvalues[r] = Eigen::VectorXd(e.M_p_eigenvalues);
      if (with_modes && e.M_p_eigenvalues(0) > 0.0) {
        try {
          modes[r] = modal_frequencies_hz(Eigen::MatrixXd(e.M_p), stiffness);
        } catch (const std::invalid_argument&) {
          // not positive definite by Cholesky: no modes for this replicate
        }
      }
    } catch (const std::invalid_argument&) {
      // a resample that cannot identify the parameters (too few distinct rows): a failed replicate
    }
  });

  PhysicalBootstrap boot;
  boot.replicates = options.bootstrap;
  boot.seed = options.seed;
  boot.level = options.confidence;
  std::vector<const Values*> present;
  for (const Values& v : values) {
    if (v.empty()) {
      ++boot.failed;
    } else {
      present.push_back(&v);
    }
  }
  Values full;
  flatten(estimate, full);
  const Eigen::Index struts = estimate.strut_mass.size();
  const Group groups[] = {{1, 1, &PhysicalBootstrap::mass},          {3, 1, &PhysicalBootstrap::center_of_mass},
                          {3, 3, &PhysicalBootstrap::inertia},       {3, 1, &PhysicalBootstrap::principal_moments},
                          {struts, 1, &PhysicalBootstrap::strut_mass}, {6, 6, &PhysicalBootstrap::M_p}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool estimated_struts = estimate.strut_masses != StrutMasses::Geometry;
  std::size_t offset = 0;
  std::vector<double> column(present.size());
  for (const Group& g : groups) {
    EntryUncertainty& u = boot.*(g.member);
    u.standard_errors.setConstant(g.rows, g.cols, nan);
    u.lower.setConstant(g.rows, g.cols, nan);
    u.upper.setConstant(g.rows, g.cols, nan);
    const bool known = g.member == &PhysicalBootstrap::strut_mass && !estimated_struts;
    for (Eigen::Index j = 0; j < g.cols; ++j)
      for (Eigen::Index i = 0; i < g.rows; ++i, ++offset) {
        if (known) {  // the geometry's strut masses: not estimated, no uncertainty
          u.standard_errors(i, j) = 0.0;
          u.lower(i, j) = u.upper(i, j) = full[offset];
          continue;
        }
        if (present.size() < 2) continue;
        double mean = 0.0;
        for (std::size_t r = 0; r < present.size(); ++r) mean += (column[r] = (*present[r])[offset]);
        mean /= static_cast<double>(present.size());
        double sum2 = 0.0;
        for (double x : column) sum2 += (x - mean) * (x - mean);
        u.standard_errors(i, j) = std::sqrt(sum2 / static_cast<double>(present.size() - 1));
        std::sort(column.begin(), column.end());
        u.lower(i, j) = quantile(column, 0.5 * (1.0 - options.confidence));
        u.upper(i, j) = quantile(column, 0.5 * (1.0 + options.confidence));
      }
  }
  boot.M_p_eigenvalues =
      spdfit::detail::summarize_spectrum(estimate.M_p_eigenvalues, eigenvalues, options.confidence);
  if (with_modes) boot.modes_hz = spdfit::detail::summarize_spectrum(*estimate.modes_hz, modes, options.confidence);
  if (present.size() < 2) {
    estimate.warnings.push_back(Warning(Code::BootstrapNotice, "the bootstrap has no standard errors: " + std::to_string(boot.failed) + " of " +
                                std::to_string(boot.replicates) + " replicates had no estimate"));
  } else if (boot.failed * 100 > boot.replicates) {
    estimate.warnings.push_back(Warning(Code::BootstrapNotice, std::to_string(boot.failed) + " of " + std::to_string(boot.replicates) +
                                " bootstrap replicates had no estimate and were left out"));
  }
  estimate.bootstrap = std::move(boot);
}

}  // namespace spdfit::hexapod::detail
