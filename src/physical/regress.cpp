// Physically consistent least squares for K rigid bodies (physical/regress.hpp): the triangular
// factor of the whitened regressor, its identifiability, and the shared cone solver.
#include "spdfit/physical/regress.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "numerics/parallel.hpp"
#include "physical/cone.hpp"
#include "physical/cone_solver.hpp"
#include "physical/identifiability.hpp"
#include "physical/linear_criterion.hpp"
#include "physical/replicates.hpp"
#include "spdfit/format.hpp"
#include "spdfit/rank.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::physical {

namespace {

using detail::kBodyCoordinates;

// Where the unconstrained fit lies on or outside the cone, the barrier path starts this fraction of
// each body's largest eigenvalue inside.
constexpr double kStartInside = 1e-2;
// The rounding of the pseudo-inertia's computed eigenvalues relative to the largest: what
// "physically consistent" allows below zero.
constexpr double kConsistencyRounding = 64.0 * std::numeric_limits<double>::epsilon();
// The ridge's size relative to the criterion's curvature where the data leave directions undetermined
// (LinearCriterion::set_ridge): far below what any determined combination is known to.
constexpr double kRidge = 1e-12;
// The residual variance that normalizes the criterion beside a prior is at least this fraction of
// the mean square of the outputs (exact data have none).
constexpr double kVarianceFloor = 1e-24;

// The position in the request's order of URDF entry e (m, mc_x, mc_y, mc_z, xx, xy, xz, yy, yz, zz).
constexpr int kUrdfPosition[2][10] = {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, {0, 1, 2, 3, 4, 5, 7, 6, 8, 9}};

int position(ParamOrder order, int urdf_entry) { return kUrdfPosition[order == ParamOrder::Pinocchio][urdf_entry]; }

// A body's ten parameters (request order) in URDF order.
Eigen::Matrix<double, 10, 1> urdf_order(const Eigen::Ref<const Eigen::VectorXd>& phi, ParamOrder order) {
  Eigen::Matrix<double, 10, 1> out;
  for (int e = 0; e < 10; ++e) out(e) = phi(position(order, e));
  return out;
}

RigidBodyInertia body_of(const Eigen::Matrix<double, 10, 1>& u) {
  RigidBodyInertia body;
  body.mass = u(0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(u(0) > 0.0) || !u.allFinite()) {
    body.center_of_mass.setConstant(nan);
    body.inertia.setConstant(nan);
    return body;
  }
  body.center_of_mass = u.segment<3>(1) / u(0);
  const Eigen::Matrix3d I_o = detail::inertia_of_urdf(u);
  const Eigen::Vector3d& c = body.center_of_mass;
  // I_o = I_c + m (|c|^2 1 - c c^T).
  body.inertia = I_o - u(0) * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return body;
}

struct Whitened {
  Eigen::MatrixXd Y, tau;
  Eigen::Index outputs = 1, samples = 0;
};

// The problem in the factor's scaled units, and what the replicates share with the full fit.
struct Setup {
  detail::ConeLayout layout;
  std::vector<double> length;                 // L_k
  std::vector<Eigen::Matrix4d> prior_pseudo;  // J0_k (SI), empty without a prior
  std::vector<std::string> names;
};

// M: theta -> phi (request order) for the lengths; and its inverse.
Eigen::MatrixXd coordinate_map(const Setup& s, Eigen::Index p, ParamOrder order, bool inverse) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(p, p);
  for (int k = 0; k < s.layout.bodies; ++k) {
    const Eigen::Matrix<double, 10, 10> T = inverse ? detail::coordinates_from_urdf(s.length[static_cast<std::size_t>(k)])
                                                    : detail::urdf_from_coordinates(s.length[static_cast<std::size_t>(k)]);
    const int base = kBodyCoordinates * k;
    for (int e = 0; e < 10; ++e)
      for (int a = 0; a < 10; ++a) {
        if (inverse) {
          M(base + a, base + position(order, e)) = T(a, e);
        } else {
          M(base + position(order, e), base + a) = T(e, a);
        }
      }
  }
  return M;
}

// L_k = ||Y_m|| / RMS ||Y_mc_j||: the length that gives body k's mass and first-moment columns the
// same size in the solver's coordinates (1 m where the data give none).
std::vector<double> lengths(const Eigen::MatrixXd& R11, int bodies, ParamOrder order) {
  std::vector<double> out;
  for (int k = 0; k < bodies; ++k) {
    const int base = kBodyCoordinates * k;
    const double mass = R11.col(base + position(order, 0)).norm();
    double first = 0.0;
    for (int j = 1; j <= 3; ++j) first += R11.col(base + position(order, j)).squaredNorm();
    first = std::sqrt(first / 3.0);
    const double L = mass / first;
    out.push_back(std::isfinite(L) && L > 0.0 ? L : 1.0);
  }
  return out;
}

// The fit from the factor; *full_phi (when given) receives every parameter, the undetermined ones
// too (the base parameters are determined whatever they are).
RegressResult fit_factor(const TriangularFactor& factor, const RegressRequest& request, const Setup& setup,
                         Eigen::Index rows, bool reported, Eigen::VectorXd* full_phi = nullptr) {
  RegressResult out;
  out.bodies = request.bodies;
  out.param_order = request.param_order;
  out.consistent_requested = request.consistent;
  out.prior_used = !setup.prior_pseudo.empty();
  out.rows = rows;
  out.names = setup.names;
  const Eigen::Index p = factor.n();
  const double theta_scale = std::ldexp(1.0, factor.exponent_a() - factor.exponent_b());
  const double unscale2 = std::ldexp(1.0, 2 * factor.exponent_b());
  const Eigen::MatrixXd R11 = factor.R11();
  const Eigen::VectorXd r12 = factor.R12().col(0);
  const double rho2 = factor.R22().squaredNorm();

  const double cutoff = rank_cutoff(request.rank_tolerance.value_or(-1.0), rows, p);
  out.identifiability = detail::identifiability(R11, setup.names, cutoff);
  const Eigen::Index rank = out.identifiability.rank;

  // The unconstrained fit: the minimum-norm solution in unit-norm columns.
  Eigen::VectorXd scale(p);
  for (Eigen::Index j = 0; j < p; ++j) {
    const double n = R11.col(j).norm();
    scale(j) = n > 0.0 ? 1.0 / n : 1.0;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R11 * scale.asDiagonal(), Eigen::ComputeThinU | Eigen::ComputeThinV);
  Eigen::VectorXd coefficients = Eigen::VectorXd::Zero(p);
  const Eigen::VectorXd Uty = svd.matrixU().transpose() * r12;
  for (Eigen::Index k = 0; k < rank; ++k) coefficients += svd.matrixV().col(k) * (Uty(k) / svd.singularValues()(k));
  const Eigen::VectorXd phi_ls = scale.cwiseProduct(coefficients);
  const double rss_ls = (R11 * phi_ls - r12).squaredNorm() + rho2;
  out.criterion_unconstrained = rss_ls * unscale2;

  Setup local = setup;
  local.length = lengths(R11, request.bodies, request.param_order);
  const Eigen::MatrixXd M = coordinate_map(local, p, request.param_order, false);
  const Eigen::MatrixXd Minv = coordinate_map(local, p, request.param_order, true);
  const Eigen::VectorXd theta_ls = Minv * phi_ls;

  const double total = r12.squaredNorm() + rho2;
  double f0 = total > 0.0 ? total : 1.0;
  if (out.prior_used) {
    const double variance = rss_ls / static_cast<double>(std::max<Eigen::Index>(rows - rank, 1));
    f0 = std::max(variance, kVarianceFloor * total / static_cast<double>(std::max<Eigen::Index>(rows, 1)));
    if (!(f0 > 0.0)) f0 = 1.0;
  }
  detail::LinearCriterion criterion(R11 * M, r12, rho2, f0);
  if (out.prior_used) {
    std::vector<Eigen::Matrix4d> prior;
    for (int k = 0; k < request.bodies; ++k) {
      const double L = local.length[static_cast<std::size_t>(k)];
      const Eigen::Vector4d s(1.0 / L, 1.0 / L, 1.0 / L, 1.0);
      prior.push_back(theta_scale * s.asDiagonal() * setup.prior_pseudo[static_cast<std::size_t>(k)] * s.asDiagonal());
    }
    criterion.set_prior(local.layout, prior, request.prior_weight);
  } else if (rank < p && request.consistent) {
    // Undetermined directions and no prior: a ridge of kRidge times the Hessian's mean diagonal
    // bounds the barrier problems (the determined combinations move by about kRidge relative).
    const double mean_diagonal = (R11 * M).colwise().squaredNorm().mean() * 2.0 / f0;
    criterion.set_ridge(kRidge * mean_diagonal);
  }

  Eigen::VectorXd theta = theta_ls;
  out.converged = true;
  std::string failure;
  if (request.consistent && (out.prior_used || !detail::strictly_feasible(local.layout, theta_ls))) {
    const Eigen::VectorXd start = detail::pushed_inside(local.layout, theta_ls, kStartInside);
    const detail::SolveResult solved = detail::solve_constrained(criterion, local.layout, start, request.max_iterations);
    theta = solved.theta;
    out.iterations = solved.iterations;
    out.converged = solved.converged;
    failure = solved.message;
  }
  if (!theta.allFinite()) {
    out.status = Status::NumericalFailure;
    out.message = "physically consistent regression failed: " +
                  (failure.empty() ? std::string("no finite estimate") : failure);
    return out;
  }
  out.status = Status::Success;
  const Eigen::VectorXd phi_scaled = M * theta;
  const Eigen::VectorXd phi = phi_scaled / theta_scale;
  out.criterion = criterion.residual_squares(theta) * unscale2;
  out.residual_rms = std::sqrt(out.criterion / static_cast<double>(std::max<Eigen::Index>(rows, 1)));
  out.base_parameters = out.identifiability.base * phi;
  if (full_phi) *full_phi = phi;

  out.parameters = phi;
  if (!out.prior_used) {
    for (Eigen::Index j = 0; j < p; ++j)
      if (!out.identifiability.determined[static_cast<std::size_t>(j)])
        out.parameters(j) = std::numeric_limits<double>::quiet_NaN();
  }
  out.physically_consistent = true;
  for (int k = 0; k < request.bodies; ++k) {
    RegressBody b;
    b.parameters = out.parameters.segment<10>(kBodyCoordinates * k);
    b.determined = b.parameters.allFinite();
    b.inertia = body_of(urdf_order(b.parameters, request.param_order));
    const Eigen::Vector4d d = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(detail::body_matrix(theta, k),
                                                                              Eigen::EigenvaluesOnly)
                                  .eigenvalues() /
                              theta_scale;
    b.pseudo_inertia_min_eig = d(0);
    b.physically_consistent = d(0) >= -kConsistencyRounding * std::abs(d(3));
    out.physically_consistent = out.physically_consistent && b.physically_consistent;
    out.body.push_back(b);
  }
  out.extra = out.parameters.tail(p - kBodyCoordinates * request.bodies);
  if (!reported) return out;

  if (request.consistent) {
    const detail::ConeCertificate c = detail::kkt_certificate(criterion, local.layout, theta);
    out.certificate.stationarity = c.stationarity;
    out.certificate.primal_min_eig = c.primal_min_eig / theta_scale;
    out.certificate.dual_min_eig = c.dual_min_eig;
    out.certificate.complementarity = c.complementarity;
    out.certificate.duality_gap = std::abs(c.complementarity);  // the criterion is convex
  } else {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out.certificate = {nan, nan, nan, nan, nan};
  }
  if (!out.converged) {
    out.warnings.push_back(Warning(Code::NotConverged, "the optimizer did not converge" + (failure.empty() ? std::string() : ": " + failure) +
                           "; the estimate is the last iterate"));
  }
  if (!out.identifiability.undetermined.empty()) {
    std::string list;
    for (const UndeterminedCombination& u : out.identifiability.undetermined) list += (list.empty() ? "" : "; ") + u.text;
    if (out.prior_used) {
      out.warnings.push_back(Warning(Code::RankDeficient, "the data do not determine " + std::to_string(out.identifiability.undetermined.size()) +
                             " combination(s) of the parameters (" + list + "): the prior sets them"));
    } else {
      out.warnings.push_back(Warning(Code::RankDeficient, "the data do not determine " + std::to_string(out.identifiability.undetermined.size()) +
                             " combination(s) of the parameters (" + list +
                             "): the parameters they reach are reported as null; the base parameters are determined. "
                             "Give a prior (`prior`, e.g. from CAD) to set them"));
    }
  }
  if (!request.consistent && !out.physically_consistent) {
    std::string which;
    for (int k = 0; k < request.bodies; ++k)
      if (!out.body[static_cast<std::size_t>(k)].physically_consistent) which += (which.empty() ? "" : ", ") + std::to_string(k + 1);
    out.warnings.push_back(Warning(Code::PhysicalNotice, "the unconstrained estimate is not physically consistent (bodies " + which +
                           "): no rigid body has these mass properties"));
  }
  return out;
}

}  // namespace

std::string_view to_string(ParamOrder order) { return order == ParamOrder::Pinocchio ? "pinocchio" : "urdf"; }

std::optional<ParamOrder> parse_param_order(std::string_view name) {
  if (name == "urdf") return ParamOrder::Urdf;
  if (name == "pinocchio") return ParamOrder::Pinocchio;
  return std::nullopt;
}

std::vector<std::string> body_parameter_names(int k, ParamOrder order) {
  static const char* const kUrdf[10] = {"m", "mc_x", "mc_y", "mc_z", "I_xx", "I_xy", "I_xz", "I_yy", "I_yz", "I_zz"};
  std::vector<std::string> out(10);
  for (int e = 0; e < 10; ++e) out[static_cast<std::size_t>(position(order, e))] = std::string(kUrdf[e]) + "_" + std::to_string(k);
  return out;
}

bool RegressRequest::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (bodies < 1) return fail("`bodies` must be at least 1");
  if (max_iterations < 1) return fail("`max_iterations` must be at least 1");
  if (rank_tolerance && !(*rank_tolerance >= 0.0 && *rank_tolerance < 1.0))
    return fail("`rank_tolerance` must be a number in [0, 1)");
  if (bootstrap < 0) return fail("`bootstrap` must be a number of replicates >= 0");
  if (!(confidence > 0.0 && confidence < 1.0))
    return fail("`confidence` must be a fraction strictly between 0 and 1 (0.95 for 95%)");
  if (!(prior_weight > 0.0) || !std::isfinite(prior_weight)) return fail("`prior_weight` must be a finite number > 0");
  if (!prior.empty() && static_cast<int>(prior.size()) != bodies) {
    return fail("the prior (`prior`) has " + std::to_string(prior.size()) + " bodies, but `bodies` is " +
                std::to_string(bodies));
  }
  if (!prior.empty() && !consistent) {
    return fail("a prior (`prior`) keeps the bodies physically consistent: it cannot be given with `unconstrained`");
  }
  for (std::size_t k = 0; k < prior.size(); ++k) {
    std::string why;
    if (!is_well_formed(prior[k], &why)) return fail("prior body " + std::to_string(k + 1) + ": " + why);
    const Eigen::Vector4d d = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(pseudo_inertia(prior[k]),
                                                                              Eigen::EigenvaluesOnly)
                                  .eigenvalues();
    if (!(d(0) > kConsistencyRounding * d(3))) {
      return fail("prior body " + std::to_string(k + 1) +
                  " is not strictly physically consistent (its pseudo-inertia's smallest eigenvalue is " +
                  format_number(d(0)) + "): the log-determinant divergence needs a positive definite one "
                                        "(repair it with `spdfit inertia repair`)");
    }
  }
  if (noise_cov.size() > 0) {
    if (noise_cov.rows() != noise_cov.cols()) return fail("`noise_cov` must be square");
    if (!noise_cov.allFinite()) return fail("`noise_cov` must have finite entries");
    if ((noise_cov - noise_cov.transpose()).cwiseAbs().maxCoeff() > 1e-12 * noise_cov.cwiseAbs().maxCoeff())
      return fail("`noise_cov` must be symmetric");
    const Eigen::LLT<Eigen::MatrixXd> llt(noise_cov);
    if (llt.info() != Eigen::Success) return fail("`noise_cov` must be positive definite");
  }
  return true;
}

RegressResult regress(const Eigen::MatrixXd& Y, const Eigen::MatrixXd& tau, const RegressRequest& request) {
  std::string error;
  if (!request.is_valid(&error)) throw OptionError(error);
  const Eigen::Index p = Y.cols(), rows = Y.rows();
  const int K = request.bodies;
  if (p < kBodyCoordinates * K) {
    throw InputError("Y has " + std::to_string(p) + " columns: " + std::to_string(K) +
                                (K == 1 ? " body needs" : " bodies need") + " at least " +
                                std::to_string(kBodyCoordinates * K) + " (10 per body, then any extra columns)", Code::DataShape);
  }
  if (tau.cols() != 1 || tau.rows() != rows) {
    throw InputError("tau must be one column with Y's " + std::to_string(rows) + " rows, not " +
                                std::to_string(tau.rows()) + " x " + std::to_string(tau.cols()), Code::DataShape);
  }
  if (rows == 0) throw InputError("regression needs at least one row of data", Code::DataShape);
  if (!Y.allFinite() || !tau.allFinite()) throw InputError("Y and tau must be finite (no NaN or Inf)", Code::DataValue);
  const Eigen::Index d = request.noise_cov.size() > 0 ? request.noise_cov.rows() : 1;
  if (rows % d != 0) {
    throw InputError("Y has " + std::to_string(rows) + " rows, not a multiple of the " + std::to_string(d) +
                                " outputs per sample that `noise_cov` has", Code::DataShape);
  }
  Whitened w{Y, tau, d, rows / d};
  if (d > 1 || request.noise_cov.size() > 0) {
    // W^1/2 = L^-1 (noise_cov = L L^T) on each sample's block of d rows: column j of Y is d x samples.
    const Eigen::LLT<Eigen::MatrixXd> llt(request.noise_cov);
    const Eigen::MatrixXd L = llt.matrixL();
    for (Eigen::Index j = 0; j < p; ++j) {
      Eigen::Map<Eigen::MatrixXd> block(w.Y.col(j).data(), d, w.samples);
      L.triangularView<Eigen::Lower>().solveInPlace(block);
    }
    Eigen::Map<Eigen::MatrixXd> block(w.tau.data(), d, w.samples);
    L.triangularView<Eigen::Lower>().solveInPlace(block);
  }

  Setup setup;
  setup.layout.bodies = K;
  setup.layout.free = static_cast<int>(p) - kBodyCoordinates * K;
  for (int k = 0; k < K; ++k) {
    const std::vector<std::string> names = body_parameter_names(k + 1, request.param_order);
    setup.names.insert(setup.names.end(), names.begin(), names.end());
  }
  for (Eigen::Index j = kBodyCoordinates * K; j < p; ++j) setup.names.push_back("x_" + std::to_string(j - kBodyCoordinates * K + 1));
  for (const RigidBodyInertia& body : request.prior) setup.prior_pseudo.push_back(pseudo_inertia(body));

  const TriangularFactor factor = TriangularFactor::from_data(w.Y, w.tau);
  RegressResult out = fit_factor(factor, request, setup, rows, true);
  out.samples = w.samples;
  out.outputs = d;
  if (!out.ok() || request.bootstrap <= 0) return out;

  // The bootstrap over samples: each replicate's factor from the rows counted by their sample's draw.
  const auto replicates = static_cast<std::size_t>(request.bootstrap);
  std::vector<std::optional<Eigen::VectorXd>> parameters(replicates), base(replicates);
  RegressRequest quiet = request;
  quiet.bootstrap = 0;
  spdfit::detail::parallel_for(replicates, request.threads, [&](std::size_t r) {
    const std::vector<std::uint32_t> sample_counts = detail::resample_counts(w.samples, request.seed, r);
    std::vector<std::uint32_t> counts(static_cast<std::size_t>(rows));
    for (Eigen::Index i = 0; i < rows; ++i) counts[static_cast<std::size_t>(i)] = sample_counts[static_cast<std::size_t>(i / d)];
    try {
      TriangularFactor f(p, 1);
      f.append(w.Y, w.tau, counts);
      Eigen::VectorXd full;
      const RegressResult fit = fit_factor(f, quiet, setup, rows, false, &full);
      if (!fit.ok()) return;
      parameters[r] = fit.parameters;
      // The base parameters of the full fit's combinations (the replicate's own may pivot otherwise).
      base[r] = Eigen::VectorXd(out.identifiability.base * full);
    } catch (const std::invalid_argument&) {
    }
  });
  RegressBootstrap b;
  b.replicates = request.bootstrap;
  b.seed = request.seed;
  b.level = request.confidence;
  for (const auto& r : parameters) b.failed += r ? 0 : 1;
  const detail::EntrySummary ps = detail::summarize(p, parameters, request.confidence);
  const detail::EntrySummary bs = detail::summarize(out.identifiability.rank, base, request.confidence);
  b.parameter_se = ps.standard_errors;
  b.parameter_lower = ps.lower;
  b.parameter_upper = ps.upper;
  b.base_se = bs.standard_errors;
  b.base_lower = bs.lower;
  b.base_upper = bs.upper;
  out.bootstrap = b;
  if (b.failed > 0) {
    out.warnings.push_back(Warning(Code::BootstrapNotice, std::to_string(b.failed) + " of " + std::to_string(b.replicates) +
                           " bootstrap replicates failed and are left out"));
  }
  return out;
}

}  // namespace spdfit::physical
