#include "spdfit/hexapod/physical.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "estimators/diagnostics.hpp"
#include "hexapod/kinematics.hpp"
#include "hexapod/physical_fit.hpp"
#include "hexapod/physical_solver.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/row_scores.hpp"
#include "robust/m_estimator.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/rank.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit::hexapod {

namespace {

// A singular value of the 21 x p design below this fraction of the largest is a confounded
// combination: exact confounding (the cubic hexapod's common strut mass) gives about 1e-16, and a
// parameter known to only 1e-10 of the others' scale is not estimated from measured data.
constexpr double kDesignTolerance = 1e-10;
// Where the least-squares start lies on the boundary of the cone, the errors-in-variables
// iteration starts this fraction of P's largest eigenvalue inside.
constexpr double kStartInside = 1e-2;
// The rounding of the pseudo-inertia's computed eigenvalues (from theta, through the 4 x 4
// eigensolver), relative to the largest: what "physically consistent" allows below zero.
constexpr double kConsistencyRounding = 64.0 * std::numeric_limits<double>::epsilon();
// Symmetry of the noise covariances, relative to their largest entry.
constexpr double kSymmetryTolerance = 1e-12;
// A payload mass beyond this factor of the geometry's (either way) is not this hexapod's payload in
// the geometry's SI units: data in kN or mm/s^2 are off by 1000, while a payload a hundred times
// heavier or lighter than the one the geometry was designed for is not one it would carry.
constexpr double kPlausibleMassFactor = 100.0;
// A factor as a user types it: a power of ten as its digits (1000, 0.001), else 3 digits.
std::string factor_text(double factor) {
  const double decade = std::pow(10.0, std::round(std::log10(factor)));
  if (std::abs(factor / decade - 1.0) < 1e-12 && factor >= 1.0 && factor < 1e15) {
    return std::to_string(static_cast<long long>(std::llround(factor)));
  }
  return format_number(factor, factor < 1.0 ? Precision::Full : Precision::Brief);
}

// The message for a payload mass `mass` (kg), from `fitted`, that is not positive or more than
// kPlausibleMassFactor from the geometry's `nominal`. `scale` is the data's own scale against the
// geometry's (the trace of the generic least-squares M_p over that of the geometry's M_p; NaN when
// unknown): off by a power of ten, it names the unit. A negative mass is what forces in kN give
// when the struts' known masses are part of the model, so the scale, not the mass, says by how much.
std::string implausible_mass(const std::string& fitted, double mass, double nominal, double scale) {
  const auto kg = [](double x) { return format_number(x) + " kg"; };
  std::string text = fitted + ", " +
                     (mass > 0.0 ? format_number(mass > nominal ? mass / nominal : nominal / mass) + " times " +
                                       (mass > nominal ? "above" : "below") + " the geometry's " + kg(nominal)
                                 : "not a positive one, where the geometry's is " + kg(nominal));
  const bool scale_off = std::isfinite(scale) && scale > 0.0 &&
                         (scale < 1.0 / kPlausibleMassFactor || scale > kPlausibleMassFactor);
  const double factor = scale_off ? 1.0 / scale : mass > 0.0 ? nominal / mass : 0.0;  // to multiply the forces by
  if (!(factor > 0.0)) {
    return text + ": are the forces and accelerations in the geometry's units (SI: N and m/s^2), with the geometry's "
                  "signs and strut order, and tared (`offsets` rest with rest rows)?";
  }
  const double decade = std::pow(10.0, std::round(std::log10(factor)));
  const bool round_decade = std::abs(factor / decade - 1.0) < 0.2;
  std::string units;
  if (round_decade && std::abs(decade - 1000.0) < 1e-9) units = " (kN instead of N?)";
  if (round_decade && std::abs(decade - 1e-3) < 1e-12) units = " (mN instead of N, or accelerations in mm/s^2?)";
  if (scale_off) {
    text += "; the data's scale (the least-squares M_p's trace) is " + format_number(scale) +
            " times the geometry's M_p's";
  }
  return text + ": the geometry is in SI units (N, m/s^2, m, kg), and the data are probably in others" + units +
         ": multiply the forces by " + factor_text(round_decade ? decade : factor) + " (`scale_b` " +
         factor_text(round_decade ? decade : factor) + "; or the accelerations by its inverse, `scale_a`)";
}

// Throws the implausible payload's error (Code::PhysicalData) unless `mass` is within
// kPlausibleMassFactor of the geometry's; `scale` as implausible_mass takes it.
void check_plausible_mass(double mass, const Geometry& geometry, const std::string& fitted,
                          double scale = std::numeric_limits<double>::quiet_NaN()) {
  const double nominal = geometry.payload_mass;
  if (mass > 0.0 && mass >= nominal / kPlausibleMassFactor && mass <= nominal * kPlausibleMassFactor) return;
  throw InputError(implausible_mass(fitted, mass, nominal, scale) + "; `no_plausibility_check` fits them as they are",
                   Code::PhysicalData, "no_plausibility_check");
}

// The warning for forces that look untared (spdfit::detail::untared_columns): the load is in every
// row, moving or not.
std::optional<Warning> untared_warning(const Eigen::MatrixXd& B, const PhysicalOptions& options) {
  if (options.noise_cov_b.rows() != B.cols()) return std::nullopt;
  const std::string columns = spdfit::detail::untared_columns(B, options.rest_mean_b, options.noise_cov_b.diagonal(),
                                                              options.rest_rows);
  if (columns.empty()) return std::nullopt;
  return Warning(Code::Bias,
                 "the forces look untared: the rest rows' means are far from 0 and the data's column means are the "
                 "same (" + columns + "): a static load is still in B, and the fit of B ~= A M_p takes it for "
                 "payload; `offsets` rest subtracts the rest rows' means",
                 "offsets");
}

bool valid_covariance(const Eigen::MatrixXd& S, const char* name, bool& definite, std::string* error) {
  definite = true;
  if (S.size() == 0) return true;
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (S.rows() != 6 || S.cols() != 6) {
    return fail(std::string("`") + name + "` must be 6 x 6 (one row and column per strut), not " +
                std::to_string(S.rows()) + " x " + std::to_string(S.cols()));
  }
  if (!S.allFinite()) return fail(std::string("`") + name + "` must have finite entries");
  if ((S - S.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * S.cwiseAbs().maxCoeff()) {
    return fail(std::string("`") + name + "` must be symmetric");
  }
  const Eigen::VectorXd w = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (S + S.transpose()),
                                                                           Eigen::EigenvaluesOnly)
                                .eigenvalues();
  const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * std::max(w.cwiseAbs().maxCoeff(), 0.0);
  if (w(0) < -rounding) return fail(std::string("`") + name + "` must be positive semidefinite (a covariance)");
  definite = w(0) > rounding;
  return true;
}

std::string list_text(const Eigen::VectorXd& v) { return format_numbers(v); }

}  // namespace

std::string_view to_string(StrutMasses strut_masses) {
  switch (strut_masses) {
    case StrutMasses::Common:
      return "common";
    case StrutMasses::Each:
      return "each";
    case StrutMasses::Geometry:
      break;
  }
  return "geometry";
}

std::optional<StrutMasses> parse_strut_masses(std::string_view name) {
  if (name == "geometry") return StrutMasses::Geometry;
  if (name == "common") return StrutMasses::Common;
  if (name == "each") return StrutMasses::Each;
  return std::nullopt;
}

std::string_view to_string(PhysicalCriterion criterion) {
  return criterion == PhysicalCriterion::LeastSquares ? "ls" : "eiv";
}

std::optional<PhysicalCriterion> parse_physical_criterion(std::string_view name) {
  if (name == "eiv") return PhysicalCriterion::ErrorsInVariables;
  if (name == "ls") return PhysicalCriterion::LeastSquares;
  return std::nullopt;
}

bool PhysicalOptions::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  bool definite_a = true, definite_b = true;
  if (!valid_covariance(noise_cov_a, "noise_cov_a", definite_a, error)) return false;
  if (!valid_covariance(noise_cov_b, "noise_cov_b", definite_b, error)) return false;
  if (!definite_a && !definite_b) {
    return fail("`noise_cov_a` and `noise_cov_b` are both singular: at least one must be positive definite");
  }
  if (max_iterations < 1) return fail("`max_iterations` must be at least 1");
  if (rank_tolerance && !(*rank_tolerance >= 0.0 && *rank_tolerance < 1.0)) {
    return fail("`rank_tolerance` must be a number in [0, 1)");
  }
  if (bootstrap < 0) return fail("`bootstrap` must be a number of replicates >= 0");
  if (tare && intercept) {
    return fail("`offsets` is one of rest (the rest rows' means subtracted) and estimate (constants fitted), not both");
  }
  if (robust_tuning && !(std::isfinite(*robust_tuning) && *robust_tuning > 0.0)) {
    return fail("`robust_tuning` must be a finite number > 0");
  }
  if (robust_tuning && robust == RobustLoss::None) return fail("`robust_tuning` needs `robust`");
  if (!(confidence > 0.0 && confidence < 1.0)) {
    return fail("`confidence` must be a fraction strictly between 0 and 1 (0.95 for 95%)");
  }
  return true;
}

PhysicalDesign physical_design(const Geometry& geometry, StrutMasses strut_masses) {
  const detail::PhysicalModel model = detail::physical_model(geometry, strut_masses);
  PhysicalDesign design;
  design.parameters = model.parameters;
  design.length_scale = model.length;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(detail::design_matrix(model), Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  design.rank = numerical_rank(s, kDesignTolerance);
  design.condition = design.rank == model.parameters ? s(0) / s(model.parameters - 1)
                                                     : std::numeric_limits<double>::infinity();
  design.null_space = svd.matrixV().rightCols(model.parameters - design.rank);
  for (Eigen::Index k = 0; k < design.null_space.cols(); ++k) {
    design.confounded += (k ? "; " : "") + detail::describe_combination(model, design.null_space.col(k));
  }
  return design;
}

namespace detail {

PhysicalEstimate fit_physical(const TriangularFactor& factor, const PhysicalModel& model, const Geometry& geometry,
                              const PhysicalOptions& options, bool reported) {
  PhysicalEstimate out;
  out.criterion_kind = options.criterion;
  out.strut_masses = options.strut_masses;
  out.consistent_requested = options.consistent;
  out.m = factor.rows();
  if (factor.n() != 6 || factor.d() != 6) {
    throw std::invalid_argument("physical identification needs 6 columns in A and in B (one per strut), not " +
                                std::to_string(factor.n()) + " and " + std::to_string(factor.d()));
  }

  PhysicalData ls = physical_data(factor, model, PhysicalCriterion::LeastSquares, options.noise_cov_a,
                                  options.noise_cov_b);
  const Eigen::VectorXd sa = Eigen::JacobiSVD<Eigen::MatrixXd>(Eigen::MatrixXd(ls.R11)).singularValues();
  out.rank_a = numerical_rank(sa, rank_cutoff(options.rank_tolerance.value_or(-1.0), std::max<Eigen::Index>(out.m, 6), 6));

  // Identifiability from the data: the 36 x p design of theta -> R11 M(theta).
  Eigen::Index rank = 0;
  Eigen::MatrixXd null_space;
  const double cutoff = rank_cutoff(options.rank_tolerance.value_or(-1.0), 36, model.parameters);
  const ParamVector theta_ls = unconstrained_least_squares(ls, model, cutoff, &rank, &null_space);
  if (rank < model.parameters) {
    throw std::invalid_argument(
        "the data cannot identify the payload's " + reached_groups(model, null_space) + ": A has rank " +
        std::to_string(out.rank_a) + " of 6 (m = " + std::to_string(out.m) + (out.m == 1 ? " row" : " rows") +
        "), so the forces determine only " + std::to_string(rank) + " of the " +
        std::to_string(model.parameters) +
        " parameters; log more samples that excite the payload in every direction");
  }
  if (options.plausibility_check) {
    const double mass = payload_of(model, theta_ls / ls.theta_scale).mass;
    // The data's scale: the generic least-squares M_p (R11^-1 R12, in the data's units) against the
    // geometry's, by their traces.
    double scale = std::numeric_limits<double>::quiet_NaN();
    if (out.rank_a == 6) {
      const Matrix6d X_ls = ls.R11.triangularView<Eigen::Upper>().solve(ls.R12) / ls.theta_scale;
      scale = X_ls.trace() / joint_space_mass_matrix(geometry).trace();
    }
    check_plausible_mass(mass, geometry,
                         "the data imply a payload mass of " + format_number(mass) +
                             " kg (the unconstrained least-squares fit of the physical model)",
                         scale);
  }
  ls.f0 = ls.R12.squaredNorm() + ls.R22.squaredNorm();
  if (!(ls.f0 > 0.0)) ls.f0 = 1.0;

  ParamVector theta = theta_ls;
  int iterations = 0;
  bool converged = true;
  std::string failure;
  PhysicalData eiv;
  const bool is_eiv = options.criterion == PhysicalCriterion::ErrorsInVariables;
  if (options.consistent) {
    // The convex least-squares fit: the unconstrained one when it is strictly feasible, else the
    // barrier path from it pushed inside.
    if (!strictly_feasible(model, theta_ls)) {
      const SolveResult start = solve_constrained(ls, model, pushed_inside(model, theta_ls, kStartInside),
                                                  options.max_iterations);
      theta = start.theta;
      iterations += start.iterations;
      converged = start.converged;
      failure = start.message;
    }
    if (reported) {
      const PhysicalCertificate c = kkt_certificate(ls, model, theta);
      out.start_certificate.primal_min_eig = c.primal_min_eig;
      out.start_certificate.dual_min_eig = c.dual_min_eig;
      out.start_certificate.complementarity = c.complementarity;
      out.start_certificate.duality_gap = std::abs(c.complementarity);
    }
    if (is_eiv && converged) {
      eiv = ls;
      eiv.criterion = PhysicalCriterion::ErrorsInVariables;
      const ParamVector start = strictly_feasible(model, theta) ? theta : pushed_inside(model, theta, kStartInside);
      if (!set_normalization(eiv, model, start)) {
        failure = "the noise covariances make the criterion's weight singular at the start";
        converged = false;
      } else {
        // The criterion is not convex: two starts, the lowest local minimum wins. The barrier path
        // from the certified least-squares fit, and Newton's method without constraints from the
        // unconstrained least-squares fit: its minimum, when inside the cone, is a KKT point with
        // zero multipliers; when outside, the face it points to (or the barrier path from it pushed
        // inside) is a third start.
        std::optional<SolveResult> best;
        auto consider = [&](const SolveResult& r, bool usable) {
          iterations += r.iterations;
          if (!usable) return;
          const bool better = !best || (r.converged && !best->converged) ||
                              (r.converged == best->converged && r.f < best->f);
          if (better) best = r;
        };
        const auto budget = [&] { return std::max(options.max_iterations - iterations, 1); };
        const SolveResult free = solve_unconstrained(eiv, model, theta_ls, budget());
        const bool free_inside = free.converged && strictly_feasible(model, free.theta);
        consider(free, free_inside);
        if (!free_inside || !strictly_feasible(model, theta_ls)) {
          consider(solve_constrained(eiv, model, start, budget()), true);
          if (free.converged && !free_inside && free.theta.allFinite()) {
            // From the unconstrained minimum: the face its clipped pseudo-inertia lies on, or the
            // barrier path from it pushed inside.
            int steps = 0;
            const std::optional<SolveResult> face = solve_on_face(eiv, model, free.theta, budget(), &steps);
            iterations += steps;
            if (face) {
              consider(*face, true);
            } else {
              consider(solve_constrained(eiv, model, pushed_inside(model, free.theta, kStartInside), budget()), true);
            }
          }
        }
        theta = best->theta;
        converged = best->converged;
        failure = best->message;
      }
    }
  } else if (is_eiv) {
    eiv = ls;
    eiv.criterion = PhysicalCriterion::ErrorsInVariables;
    if (!set_normalization(eiv, model, theta_ls)) {
      failure = "the noise covariances make the criterion's weight singular at the start";
      converged = false;
    } else {
      const SolveResult fit = solve_unconstrained(eiv, model, theta_ls, options.max_iterations);
      theta = fit.theta;
      iterations = fit.iterations;
      converged = fit.converged;
      failure = fit.message;
    }
  }
  const PhysicalData& used = is_eiv ? eiv : ls;
  if (!theta.allFinite()) {
    out.status = Status::NumericalFailure;
    out.message = "physical identification failed: " + (failure.empty() ? std::string("no finite estimate") : failure);
    return out;
  }

  out.status = Status::Success;
  out.iterations = iterations;
  out.converged = converged;
  const ParamVector physical = theta / used.theta_scale;
  out.payload = payload_of(model, physical);
  if (out.payload.mass > 0.0) {
    out.principal = principal_inertia(out.payload.inertia);
  } else {  // an unconstrained fit's mass <= 0: no centre of mass, no principal axes
    out.principal.moments.setConstant(std::numeric_limits<double>::quiet_NaN());
    out.principal.axes.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  const int struts = model.parameters - kPayloadParameters;
  out.strut_mass = struts > 0 ? Eigen::VectorXd(physical.tail(struts)) : Eigen::VectorXd(geometry.strut_mass);
  out.M_p = model_mass_matrix(model, physical);
  out.M_p_eigenvalues = Eigen::SelfAdjointEigenSolver<Matrix6d>(out.M_p, Eigen::EigenvaluesOnly).eigenvalues();
  const Eigen::Vector4d pseudo =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(scaled_pseudo_inertia(physical), Eigen::EigenvaluesOnly)
          .eigenvalues();
  out.pseudo_inertia_min_eig = pseudo(0);
  // An estimate on the boundary (a rank-deficient pseudo-inertia) has computed eigenvalues of
  // +-rounding there: consistent to the rounding of P's eigenvalues.
  const double rounding = kConsistencyRounding * std::abs(pseudo(3));
  out.physically_consistent = pseudo(0) >= -rounding && out.strut_mass.minCoeff() >= -rounding;
  const double unscale = used.criterion == PhysicalCriterion::LeastSquares
                             ? std::ldexp(1.0, 2 * factor.exponent_b())
                             : 1.0;  // the errors-in-variables criterion is invariant under the scaling
  Evaluation ev;
  out.criterion = evaluate(used, model, theta, 0, ev) ? ev.f * used.f0 * unscale
                                                      : std::numeric_limits<double>::quiet_NaN();
  if (!reported) return out;

  if (options.consistent) out.certificate = kkt_certificate(used, model, theta);
  if ((geometry.strut_stiffness.array() > 0.0).all() && out.M_p_eigenvalues(0) > 0.0) {
    try {
      out.modes_hz = Vector6d(modal_frequencies_hz(Eigen::MatrixXd(out.M_p),
                                                    Eigen::MatrixXd(geometry.strut_stiffness.asDiagonal())));
    } catch (const std::invalid_argument&) {
      // positive definite by its eigenvalues but not by Cholesky: no modes
    }
  }
  if (!converged) {
    out.warnings.push_back(Warning(Code::NotConverged, "the optimizer did not converge" + (failure.empty() ? std::string() : ": " + failure) +
                           "; the estimate is the last iterate"));
  }
  if (!options.consistent && !out.physically_consistent) {
    out.warnings.push_back(Warning(Code::PhysicalNotice, 
        "the unconstrained estimate is not physically consistent (the pseudo-inertia's smallest eigenvalue is " +
        spdfit::detail::format_number(out.pseudo_inertia_min_eig) + " kg" +
        (out.strut_mass.minCoeff() < 0.0 ? ", strut masses " + list_text(out.strut_mass) + " kg" : std::string()) +
        "): no rigid body has these mass properties"));
  }
  if (options.consistent && out.pseudo_inertia_min_eig <= 1e-6 * out.payload.mass) {
    out.warnings.push_back(Warning(Code::Boundary, 
        "the estimate lies on the boundary of physical consistency (the pseudo-inertia's smallest eigenvalue is " +
        spdfit::detail::format_number(out.pseudo_inertia_min_eig) +
        " kg): the constraint is active, as for a payload whose mass lies on a plane or a line"));
  }
  if (options.consistent && struts > 0 && out.strut_mass.minCoeff() <= 1e-9 * out.payload.mass) {
    out.warnings.push_back(Warning(Code::PhysicalNotice, "an estimated strut mass is at its bound 0: strut masses " + list_text(out.strut_mass) +
                           " kg"));
  }
  return out;
}

}  // namespace detail

namespace {

PhysicalEstimate identify_from_factor(const TriangularFactor& factor, const Geometry& geometry,
                                      const PhysicalOptions& options, detail::PhysicalModel& model) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  detail::require_valid(geometry);
  const PhysicalDesign design = physical_design(geometry, options.strut_masses);
  if (design.rank < design.parameters) {
    throw std::invalid_argument(
        "`strut_masses` = " + std::string(to_string(options.strut_masses)) +
        " cannot be estimated on this geometry: " + design.confounded + " (the map from the " +
        std::to_string(design.parameters) + " parameters to M_p has rank " + std::to_string(design.rank) +
        "); use the geometry's strut masses (`strut_masses` = geometry)");
  }
  model = detail::physical_model(geometry, options.strut_masses);
  PhysicalEstimate out = detail::fit_physical(factor, model, geometry, options);
  out.design = design;
  return out;
}

// Reweightings of the robust physical fit at most, and when they stop: M_p moving by less than
// this, relative (as the generic robust fit's X; far below M_p's standard errors).
constexpr int kPhysicalReweightings = 50;
constexpr double kPhysicalSettled = 1e-8;

// The covariance of a row's residual a_i M - b_i as the physical criterion models it: M^T Sigma_A M
// + Sigma_B (the identities without covariances) for errors in variables, I for least squares.
Eigen::MatrixXd physical_residual_covariance(const Matrix6d& M, const PhysicalOptions& options) {
  if (options.criterion == PhysicalCriterion::LeastSquares) return Eigen::MatrixXd::Identity(6, 6);
  const Matrix6d Sa = options.noise_cov_a.size() ? Matrix6d(options.noise_cov_a) : Matrix6d(Matrix6d::Identity());
  const Matrix6d Sb = options.noise_cov_b.size() ? Matrix6d(options.noise_cov_b) : Matrix6d(Matrix6d::Identity());
  return M.transpose() * Sa * M + Sb;
}

// The reweightings of the robust physical fit from M and c with the scale `scale` (Huber:
// re-estimated each time), at most kPhysicalReweightings: each `fit_weighted` of the factor of the
// rows weighted by their residuals (TriangularFactor::append with weights), `counts` (empty: 1)
// multiplying the weights (a bootstrap resample). `factor` receives the last weighted factor.
struct Reweighted {
  PhysicalEstimate estimate;
  Eigen::VectorXd weights, c;
  double scale = 0.0;
  int iterations = 0;
  bool converged = false;
};

using WeightedFit = std::function<PhysicalEstimate(const TriangularFactor&)>;

Reweighted reweight(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const PhysicalOptions& options, double k,
                    Matrix6d M, Eigen::VectorXd c, double scale, const Eigen::VectorXd& counts,
                    const WeightedFit& fit_weighted, std::optional<TriangularFactor>& factor) {
  const Eigen::Index m = A.rows();
  const RobustLoss loss = options.robust;
  const double median_chi = spdfit::detail::chi_median(6);
  Reweighted out;
  for (int it = 1; it <= kPhysicalReweightings; ++it) {
    const Eigen::VectorXd u =
        spdfit::detail::whitened_residuals(A, B, M, c, physical_residual_covariance(M, options));
    if (loss == RobustLoss::Huber) {  // the scale of the rows drawn (as the generic robust fit's)
      std::vector<double> values;
      values.reserve(static_cast<std::size_t>(m));
      for (Eigen::Index i = 0; i < m; ++i) {
        if (counts.size() == 0 || counts(i) > 0) values.push_back(u(i));
      }
      if (!values.empty()) scale = spdfit::detail::median(values) / median_chi;
    }
    out.weights = spdfit::detail::robust_weights(loss, u, scale, k);
    factor.emplace(6, 6, options.intercept);
    factor->append(A, B, counts.size() ? Eigen::VectorXd(out.weights.cwiseProduct(counts)) : out.weights);
    PhysicalEstimate next = fit_weighted(*factor);
    out.iterations = it;
    if (!next.ok()) {
      out.estimate = std::move(next);
      break;
    }
    const double change = (next.M_p - M).norm(), size = std::max(next.M_p.norm(), std::numeric_limits<double>::min());
    M = next.M_p;
    c = spdfit::detail::intercept_offsets(*factor, M);
    out.estimate = std::move(next);
    if (change <= kPhysicalSettled * size || scale == 0.0) {
      out.converged = true;
      break;
    }
  }
  out.c = std::move(c);
  out.scale = scale;
  return out;
}

// The robust physical fit (PhysicalOptions::robust): weights from the residuals of the current
// M_p (and offsets), each step the physical fit of the weighted rows (TriangularFactor::append with
// weights), as spdfit::detail::robust_fit does for the generic estimators. `factor` receives the
// last weighted factor (for the offsets' weighted means).
PhysicalEstimate robust_physical(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Geometry& geometry,
                                 const PhysicalOptions& options, detail::PhysicalModel& model,
                                 std::optional<TriangularFactor>& factor) {
  const Eigen::Index m = A.rows();
  const RobustLoss loss = options.robust;
  const double k = options.robust_tuning.value_or(spdfit::detail::robust_tuning(loss, 6));
  PhysicalOptions plain = options;  // each reweighting's fit: of the weighted rows, as they are
  plain.robust = RobustLoss::None;
  plain.robust_tuning.reset();
  plain.bootstrap = 0;
  Matrix6d M;
  Eigen::VectorXd c;
  double scale = 0.0;
  PhysicalEstimate out;
  if (loss == RobustLoss::Tukey) {
    // A high-breakdown start: least trimmed squares of the generic model, whitened as the criterion.
    FitOptions trimmed;
    Method method = Method::LeastSquares;
    if (options.criterion == PhysicalCriterion::ErrorsInVariables) {
      method = Method::SpdTotalLeastSquares;
      if (options.noise_cov_a.size() && options.noise_cov_b.size()) {
        trimmed.noise = NoiseModel::from_cov(options.noise_cov_a, options.noise_cov_b);
      }
    }
    const spdfit::detail::TrimmedStart start =
        spdfit::detail::least_trimmed_squares(A, B, options.intercept, method, trimmed);
    M = Matrix6d(start.X);
    c = start.c;
    scale = start.scale;
  } else {
    factor.emplace(TriangularFactor::from_data(A, B, options.intercept));
    out = identify_from_factor(*factor, geometry, plain, model);
    if (!out.ok()) return out;
    M = out.M_p;
    c = spdfit::detail::intercept_offsets(*factor, M);
  }
  Reweighted fitted = reweight(A, B, options, k, M, c, scale, Eigen::VectorXd(),
                               [&](const TriangularFactor& f) { return identify_from_factor(f, geometry, plain, model); },
                               factor);
  out = std::move(fitted.estimate);
  if (out.ok() && !fitted.converged) {
    out.warnings.emplace_back(Code::NotConverged,
                              "the robust physical fit's weights had not settled after " +
                                  std::to_string(fitted.iterations) + " reweightings: the last fit is returned",
                              "robust");
  }
  if (out.ok() && options.bootstrap > 0) {
    // Each replicate: the rows resampled (their counts multiply the weights), reweighted from this
    // estimate with its scale, as the generic robust fit's bootstrap.
    // Each reweighting of a replicate: fit_physical without what only a report needs, the model of
    // the estimate's fits shared.
    const PhysicalOptions quiet = detail::replicate_options(plain);
    const Matrix6d M_full = out.M_p;
    const Eigen::VectorXd c_full = fitted.c;
    const double scale_full = fitted.scale;
    detail::bootstrap_physical(out, geometry, options, [&](std::size_t r) -> std::optional<PhysicalEstimate> {
      std::optional<TriangularFactor> replicate_factor;
      Reweighted again = reweight(
          A, B, options, k, M_full, c_full, scale_full, spdfit::detail::resample_weights(m, options.seed, r),
          [&](const TriangularFactor& f) { return detail::fit_physical(f, model, geometry, quiet, false); },
          replicate_factor);
      return std::move(again.estimate);
    });
  }
  out.robust = spdfit::detail::robust_report(loss, k, fitted.weights, fitted.scale, fitted.iterations, fitted.converged);
  return out;
}

}  // namespace

PhysicalEstimate identify_physical(const TriangularFactor& factor, const Geometry& geometry,
                                   const PhysicalOptions& options) {
  if (options.bootstrap > 0) {
    throw std::invalid_argument("`bootstrap` needs the rows of A and B: pass them instead of their factor");
  }
  detail::PhysicalModel model;
  return identify_from_factor(factor, geometry, options, model);
}

PhysicalEstimate identify_physical(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Geometry& geometry,
                                   const PhysicalOptions& options) {
  if (A.cols() != 6 || B.cols() != 6 || A.rows() != B.rows()) {
    throw std::invalid_argument("physical identification needs A and B of m x 6 (one column per strut), not " +
                                std::to_string(A.rows()) + " x " + std::to_string(A.cols()) + " and " +
                                std::to_string(B.rows()) + " x " + std::to_string(B.cols()));
  }
  if (A.rows() == 0) throw std::invalid_argument("physical identification needs at least one row of data");
  // Tared: the rest rows' means subtracted (the static load and the accelerometers' bias).
  Eigen::MatrixXd At, Bt;
  if (options.tare) {
    if (options.rest_mean_a.size() != 6 || options.rest_mean_b.size() != 6) {
      throw OptionError("`offsets` rest subtracts the means of rows recorded at rest: give them (`rest_a` and "
                        "`rest_b`, or a `noise` model made from them)",
                        Code::OptionConflict, "offsets");
    }
    At = A.rowwise() - options.rest_mean_a.transpose();
    Bt = B.rowwise() - options.rest_mean_b.transpose();
  }
  const Eigen::MatrixXd& Ad = options.tare ? At : A;
  const Eigen::MatrixXd& Bd = options.tare ? Bt : B;
  detail::PhysicalModel model;
  std::optional<TriangularFactor> factor;
  PhysicalEstimate out;
  if (options.robust != RobustLoss::None) {
    std::string error;
    if (!options.is_valid(&error)) throw std::invalid_argument(error);
    out = robust_physical(Ad, Bd, geometry, options, model, factor);
  } else {
    factor.emplace(TriangularFactor::from_data(Ad, Bd, options.intercept));
    out = identify_from_factor(*factor, geometry, options, model);
  }
  if (options.intercept && out.ok() && factor) out.offsets_c = spdfit::detail::intercept_offsets(*factor, out.M_p);
  if (options.tare) {
    out.tare_a = options.rest_mean_a;
    out.tare_b = options.rest_mean_b;
  } else if (!options.intercept) {
    if (std::optional<Warning> w = untared_warning(B, options)) out.warnings.push_back(std::move(*w));
  }
  // The estimate itself may still end far from any payload of this geometry (a fit that did not
  // converge on data the check let through): never reported as one.
  if (options.plausibility_check && out.ok()) {
    check_plausible_mass(out.payload.mass, geometry,
                         "the physical fit's payload mass is " + format_number(out.payload.mass) + " kg");
  }
  if (options.bootstrap > 0 && out.ok() && options.robust == RobustLoss::None) {  // robust_physical has its own
    detail::bootstrap_physical(out, Ad, Bd, model, geometry, options);
  }
  return out;
}

}  // namespace spdfit::hexapod
