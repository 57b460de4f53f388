#include "numerics/requested_rank_tolerance.hpp"
#include "spdfit/linkage/synthesis.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "dial_zeros.hpp"
#include "linkage/angles.hpp"
#include "linkage_format.hpp"
#include "linkage_inputs.hpp"
#include "spdfit/linkage/design_error.hpp"
#include "spdfit/rank.hpp"

namespace spdfit::linkage {

using Eigen::Index;
using Eigen::VectorXd;

namespace {

constexpr double kDegree = detail::kRadiansPerDegree;
// Designers keep the transmission angle within about 40..140 degrees (beyond, the coupler pushes
// the output link mostly along its length and friction takes over): outside it, a warning.
constexpr double kTransmissionLow = 40.0 * kDegree;
constexpr double kTransmissionHigh = 140.0 * kDegree;

std::string k_text(const Eigen::Vector3d& k) {
  return "k = [" + detail::format(k(0)) + ", " + detail::format(k(1)) + ", " + detail::format(k(2)) + "]";
}

VectorXd plus(double offset, const VectorXd& v) { return (v.array() + offset).matrix(); }

// Everything about one solution that follows from k and the dial zeros.
LinkageSolution describe(const Eigen::Vector3d& k, const DialZeros& zeros, const VectorXd& delta_psi,
                         const VectorXd& delta_phi, const VectorXd& weights, int branch) {
  LinkageSolution s;
  s.k = k;
  s.dial_zeros = {wrap_angle(zeros.alpha), wrap_angle(zeros.beta)};
  const VectorXd psi = plus(zeros.alpha, delta_psi), phi = plus(zeros.beta, delta_phi);
  const VectorXd root_w = detail::root_weights(weights, psi.size());
  s.design_error_norm = root_w.cwiseProduct(synthesis_rhs(psi, phi) - synthesis_matrix(psi, phi) * k).norm();
  s.lengths = link_lengths(k, &s.no_linkage_reason);
  const auto generated = generated_outputs(k, psi, phi, branch);
  if (generated) {
    s.phi_generated = *generated;
    const VectorXd err = phi - *generated;
    // stableNorm: prescribed angles may be huge (fuzzing found 1e305 rad), and a plain sum of
    // squares would overflow to Inf for a finite error.
    s.structural_error_rms = err.stableNorm() / std::sqrt(static_cast<double>(err.size()));
    s.structural_error_max = err.cwiseAbs().maxCoeff();
  } else {
    s.structural_error_rms = s.structural_error_max = std::numeric_limits<double>::quiet_NaN();
  }
  if (s.lengths) s.check = check_motion(*s.lengths, psi, phi, branch);
  return s;
}

void add_check_warnings(const std::string& which, const LinkageSolution& s,
                        std::vector<Warning>& warnings) {
  if (!s.check) return;
  if (s.check->branch_defect)
    warnings.push_back(Warning(Code::LinkageNotice, which + " linkage has a branch defect: " + s.check->branch_defect_reason));
  if (s.check->transmission.min < kTransmissionLow || s.check->transmission.max > kTransmissionHigh) {
    warnings.push_back(Warning(Code::LinkageNotice, which + " linkage's transmission angle ranges over " +
                       detail::degrees(s.check->transmission.min) + " .. " +
                       detail::degrees(s.check->transmission.max) +
                       ", outside the usual 40..140 deg: the output is poorly driven there"));
  }
}

}  // namespace

const char* to_string(SynthesisStatus status) {
  switch (status) {
    case SynthesisStatus::Success:
      return "success";
    case SynthesisStatus::NoRealLinkage:
      return "no real linkage";
    case SynthesisStatus::NotAssemblable:
      return "not assemblable";
    case SynthesisStatus::Diverged:
      return "diverged";
  }
  return "?";
}

bool SynthesisOptions::is_valid(std::string* error) const {
  auto fail = [error](const char* why) {
    if (error) *error = why;
    return false;
  };
  if ((alpha && !std::isfinite(*alpha)) || (beta && !std::isfinite(*beta)))
    return fail("dial zeros must be finite");
  if (!(gauss_newton.tolerance > 0.0) || !std::isfinite(gauss_newton.tolerance)) {
    return fail("the Gauss-Newton tolerance must be a positive number");
  }
  if (gauss_newton.max_iterations < 1) return fail("the Gauss-Newton iteration limit must be at least 1");
  return is_valid_rank_tolerance(spdfit::detail::requested_rank_tolerance(*this), "threshold", error) &&
         is_valid_rank_tolerance(spdfit::detail::requested_rank_tolerance(gauss_newton), "the Gauss-Newton threshold", error);
}

SynthesisResult synthesize(const Eigen::Ref<const VectorXd>& delta_psi_in,
                           const Eigen::Ref<const VectorXd>& delta_phi_in,
                           const Eigen::Ref<const VectorXd>& weights_in, const SynthesisOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("synthesize: " + error);
  const Index unknowns = options.fit_dial_zeros ? 5 : 3;
  detail::check_positions(delta_psi_in, delta_phi_in, weights_in, unknowns, "synthesize");
  const VectorXd delta_psi = delta_psi_in, delta_phi = delta_phi_in, weights = weights_in;

  SynthesisResult r;
  r.positions = delta_psi.size();
  r.precision_point = r.positions == unknowns;
  r.dial_zeros_fitted = options.fit_dial_zeros;
  detail::GaussNewtonSettings settings;
  settings.tolerance = options.gauss_newton.tolerance;
  settings.max_iterations = options.gauss_newton.max_iterations;
  settings.threshold = spdfit::detail::requested_rank_tolerance(options.gauss_newton);

  // 1. The design-error solution (section 3.4), with the dial zeros when they are unknowns (eq. 3.7).
  Eigen::Vector3d k_design;
  DialZeros zeros{options.alpha.value_or(0.0), options.beta.value_or(0.0)};
  std::optional<detail::DialZeroPoint> grid_start;
  if (options.fit_dial_zeros) {
    detail::DialZeroPoint start;
    if (options.alpha || options.beta) {
      start.zeros = zeros;
      start.k = design_error_synthesis(plus(zeros.alpha, delta_psi), plus(zeros.beta, delta_phi), weights,
                                       spdfit::detail::requested_rank_tolerance(options))
                    .k;
    } else {
      grid_start = detail::dial_zero_grid_start(delta_psi, delta_phi, weights, spdfit::detail::requested_rank_tolerance(options));
      if (!grid_start) {
        r.status = SynthesisStatus::NoRealLinkage;
        r.message =
            "no dial zeros on a 5-degree grid give a design-error solution that is a real linkage "
            "assemblable at every prescribed input; give a start with `alpha` and `beta`";
        return r;
      }
      start = *grid_start;
    }
    const detail::DialZeroFit fit =
        detail::fit_design_dial_zeros(delta_psi, delta_phi, weights, start, settings);
    if (!fit.gauss_newton.converged) {
      r.status = SynthesisStatus::Diverged;
      r.message = "the dial-zero fit of the design error (eq. 3.7) failed: " + fit.gauss_newton.message;
      return r;
    }
    k_design = fit.point.k;
    zeros = fit.point.zeros;
  }
  r.psi = plus(zeros.alpha, delta_psi);
  r.phi = plus(zeros.beta, delta_phi);
  const DesignErrorSolution design = design_error_synthesis(r.psi, r.phi, weights, spdfit::detail::requested_rank_tolerance(options));
  if (!options.fit_dial_zeros) k_design = design.k;
  r.rank = design.rank;
  r.condition_number = design.condition_number;
  r.scaled_condition_number = design.scaled_condition_number;
  r.used_svd = design.used_svd;
  if (r.used_svd) {
    r.warnings.push_back(Warning(Code::LinkageNotice, 
        "the synthesis matrix S is rank-deficient (rank " + std::to_string(r.rank) +
        " < 3): k is the minimum-norm solution of the edited SVD, and other linkages fit as well"));
  }

  // 2. The assembly branch that follows the prescribed outputs.
  const std::optional<int> branch = nearest_branch(k_design, r.psi, r.phi, weights);
  r.branch = branch.value_or(1);
  r.design = describe(k_design, zeros, delta_psi, delta_phi, weights, r.branch);
  if (!r.design.lengths) {
    r.status = SynthesisStatus::NoRealLinkage;
    r.message = "the design-error solution " + k_text(k_design) +
                " is not a real linkage: " + r.design.no_linkage_reason;
    return r;
  }
  if (!branch) {
    Index unreachable = 0, first = -1;
    for (Index i = 0; i < r.psi.size(); ++i) {
      if (!output_angle(k_design, r.psi(i), 1)) {
        if (unreachable++ == 0) first = i;
      }
    }
    const FourBar& bar = *r.design.lengths;
    r.status = SynthesisStatus::NotAssemblable;
    r.message = "the design-error linkage (" + k_text(k_design) + "; a1 = 1, a2 = " + detail::format(bar.a2) +
                ", a3 = " + detail::format(bar.a3) + ", a4 = " + detail::format(bar.a4) +
                ") cannot be assembled at " + std::to_string(unreachable) + " of the " +
                std::to_string(r.psi.size()) +
                " prescribed inputs, the first at psi = " + detail::degrees(r.psi(first)) +
                ": the input cannot reach them, so there is no structural error to refine. A narrower input "
                "range or other dial zeros (or fitting them) may give an assemblable linkage";
    return r;
  }
  add_check_warnings("the design", r.design, r.warnings);

  // 3. The structural-error solution (section 3.6), unless the design solution is exact.
  if (r.precision_point || !options.refine) {
    r.structural = r.design;
    return r;
  }
  Eigen::Vector3d k_structural;
  DialZeros zeros_structural = zeros;
  int iterations = 0;
  double step_norm = 0.0;
  bool rounding_limited = false;
  if (!options.fit_dial_zeros) {
    const StructuralRefinement refined =
        refine_structural_error(k_design, r.psi, r.phi, weights, r.branch, options.gauss_newton);
    if (refined.status != SynthesisStatus::Success) {
      r.status = refined.status;
      r.message = refined.message + " (started from the design-error solution " + k_text(k_design) + ")";
      return r;
    }
    k_structural = refined.k;
    iterations = refined.iterations;
    step_norm = refined.step_norm;
    rounding_limited = refined.rounding_limited;
  } else {
    // Start from the design-error fit and from the grid start, and keep the better converged
    // refinement: the design error favours positions near dead points (where D is small), so the
    // design fit can be a poor start for the structural error.
    std::vector<detail::DialZeroPoint> starts = {{k_design, zeros}};
    if (grid_start) starts.push_back(*grid_start);
    std::optional<detail::DialZeroFit> best;
    double best_objective = std::numeric_limits<double>::infinity();
    int best_branch = 1;
    std::string failure;
    for (const detail::DialZeroPoint& start : starts) {
      const auto start_objective = detail::structural_objective(delta_psi, delta_phi, weights, start);
      if (!start_objective) continue;
      const detail::DialZeroFit fit = detail::fit_structural_dial_zeros(delta_psi, delta_phi, weights, start,
                                                                        start_objective->second, settings);
      if (!fit.gauss_newton.converged) {
        if (failure.empty()) failure = fit.gauss_newton.message;
        continue;
      }
      const auto objective = detail::structural_objective(delta_psi, delta_phi, weights, fit.point);
      if (objective && objective->first < best_objective) {
        best = fit;
        best_objective = objective->first;
        best_branch = start_objective->second;
      }
    }
    if (!best) {
      r.status = failure.empty() ? SynthesisStatus::NotAssemblable : SynthesisStatus::Diverged;
      r.message = failure.empty()
                      ? "no real, assemblable linkage to start the structural-error refinement from"
                      : "structural-error refinement with dial zeros failed: " + failure;
      return r;
    }
    k_structural = best->point.k;
    zeros_structural = best->point.zeros;
    iterations = best->gauss_newton.iterations;
    step_norm = best->gauss_newton.step_norm;
    rounding_limited = best->gauss_newton.rounding_limited;
    r.branch = best_branch;
  }
  r.structural = describe(k_structural, zeros_structural, delta_psi, delta_phi, weights, r.branch);
  r.structural.iterations = iterations;
  r.structural.final_step_norm = step_norm;
  r.structural.rounding_limited = rounding_limited;
  if (rounding_limited) {
    r.warnings.push_back(Warning(Code::LinkageNotice, 
        "Gauss-Newton stopped at rounding level with ||Delta k|| = " + detail::format(step_norm) +
        " above the tolerance: the Jacobian D^-1 S is ill-conditioned, so k is only as accurate as that"));
  }
  add_check_warnings("the structural", r.structural, r.warnings);
  return r;
}

}  // namespace spdfit::linkage
