// One payload fit (fit.hpp): least squares from the triangular factor of the whitened regressor,
// the consistency constraint (m >= 0 for static poses by its one active set; the pseudo-inertia
// cone for moving poses by the shared solver), errors in variables from there, and the sandwich
// covariance.
#include "payload/fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "payload/eiv.hpp"
#include "physical/cone.hpp"
#include "physical/cone_solver.hpp"
#include "physical/identifiability.hpp"
#include "physical/linear_criterion.hpp"
#include "pipeline/row_scores.hpp"
#include "robust/m_estimator.hpp"
#include "spdfit/rank.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::payload::detail {

namespace {

namespace shared = spdfit::physical::detail;

// Samples per block appended to the factor.
constexpr Eigen::Index kBlock = 4096;
// Where the least-squares fit lies on or outside the cone, the barrier path starts this fraction
// of the pseudo-inertia's largest eigenvalue inside.
constexpr double kStartInside = 1e-2;
// Long logs start errors in variables from a fit to every stride-th sample, about kCoarseSamples of
// them, when the stride is at least kCoarseStride: Newton's method converges only linearly from
// least squares' (biased) estimate, and those steps cost a tenth on a tenth of the samples; the
// fit to all samples then takes the few quadratically convergent steps.
constexpr Eigen::Index kCoarseSamples = 10000;
constexpr Eigen::Index kCoarseStride = 4;
// The errors-in-variables criterion (a sum of 6 whitened squares per sample) at most this many times
// 6 m at the least-squares fit: noise-free data, its residuals about 1e-8 of the noise model's.
constexpr double kExactCriterion = 1e-16;
// The ridge's size relative to the criterion's curvature where the poses leave directions undetermined.
constexpr double kRidge = 1e-12;
// An eigenvalue of the pseudo-inertia (or the static mass) below this fraction of the largest (of
// the mass scale) counts as on the boundary: the constraint is active.
constexpr double kActive = 1e-6;

shared::ConeLayout cone_layout(const ParameterLayout& layout) {
  shared::ConeLayout cone;
  if (layout.moving) {
    cone.bodies = 1;
    cone.free = 6;
  } else {
    cone.bodies = 0;
    cone.nonnegative = 1;
    cone.free = 9;
  }
  return cone;
}

// M: theta -> phi; the inertial block from the scaled pseudo-inertia's coordinates (length L).
Eigen::MatrixXd coordinate_map(const ParameterLayout& layout, double L, bool inverse) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(layout.size(), layout.size());
  if (layout.moving) {
    M.topLeftCorner<10, 10>() = inverse ? shared::coordinates_from_urdf(L) : shared::urdf_from_coordinates(L);
  }
  return M;
}

// The whitening of a sample's six readings: L^-1 with Sigma_w = L L^T (none: the identity).
struct Whitening {
  bool active = false;
  Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Identity();

  template <typename Derived>
  void apply(Eigen::MatrixBase<Derived>& block) const {
    if (active) L.triangularView<Eigen::Lower>().solveInPlace(block);
  }
};

Whitening whitening(const NoiseCovariances& noise) {
  Whitening w;
  if (noise.wrench.size() == 0) return w;
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(Eigen::Matrix<double, 6, 6>(noise.wrench));
  if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0.0)) {
    throw SignalError("the wrench's noise covariance (" +
                      std::string(noise.source == "rest" ? "of the rest rows, `rest_rows`" : "`noise_std_wrench`") +
                      ") is singular: every axis needs some noise (a constant channel in the rest rows?)", Code::NoiseModel);
  }
  w.active = true;
  w.L = llt.matrixL();
  return w;
}

TriangularFactor least_squares_factor(const Kinematics& kin, const ParameterLayout& layout, const Whitening& white,
                                      const std::vector<double>& counts, bool frequency) {
  const int p = layout.size();
  const Eigen::Index m = kin.samples();
  TriangularFactor factor(p, 1);
  Eigen::MatrixXd X, w;
  std::vector<std::uint32_t> row_counts;
  for (Eigen::Index begin = 0; begin < m; begin += kBlock) {
    const Eigen::Index n = std::min(kBlock, m - begin);
    X.resize(6 * n, p);
    w.resize(6 * n, 1);
    for (Eigen::Index k = 0; k < n; ++k) {
      auto Xk = X.middleRows(6 * k, 6);
      sample_regressor(kin, begin + k, layout, Xk);
      auto wk = w.middleRows(6 * k, 6);
      wk = kin.wrench.col(begin + k);
      white.apply(Xk);
      white.apply(wk);
    }
    if (counts.empty()) {
      factor.append(X, w);
    } else if (!frequency) {
      Eigen::VectorXd row_weights(6 * n);
      for (Eigen::Index k = 0; k < n; ++k) row_weights.segment<6>(6 * k).setConstant(counts[static_cast<std::size_t>(begin + k)]);
      factor.append(X, w, row_weights);
    } else {
      row_counts.assign(static_cast<std::size_t>(6 * n), 0);
      for (Eigen::Index k = 0; k < n; ++k)
        for (int i = 0; i < 6; ++i)
          row_counts[static_cast<std::size_t>(6 * k + i)] = static_cast<std::uint32_t>(counts[static_cast<std::size_t>(begin + k)]);
      factor.append(X, w, row_counts);
    }
  }
  return factor;
}

// The minimum-norm solution of min ||R x - y|| over the columns `columns` of R (the others 0), in
// unit-norm columns, with numerical rank by `cutoff`.
Eigen::VectorXd minimum_norm(const Eigen::MatrixXd& R, const Eigen::VectorXd& y, const std::vector<int>& columns,
                             double cutoff) {
  const auto c = static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd Rs(R.rows(), c);
  Eigen::VectorXd scale(c);
  for (Eigen::Index j = 0; j < c; ++j) {
    const double n = R.col(columns[static_cast<std::size_t>(j)]).norm();
    scale(j) = n > 0.0 ? 1.0 / n : 1.0;
    Rs.col(j) = R.col(columns[static_cast<std::size_t>(j)]) * scale(j);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Rs, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Index r = numerical_rank(svd.singularValues(), cutoff);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(c);
  const Eigen::VectorXd Uty = svd.matrixU().transpose() * y;
  for (Eigen::Index k = 0; k < r; ++k) z += svd.matrixV().col(k) * (Uty(k) / svd.singularValues()(k));
  Eigen::VectorXd out = Eigen::VectorXd::Zero(R.cols());
  for (Eigen::Index j = 0; j < c; ++j) out(columns[static_cast<std::size_t>(j)]) = scale(j) * z(j);
  return out;
}

// The pseudo-inverse of a symmetric positive semidefinite H (p x p) of numerical rank r, in unit
// diagonal scaling.
Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& H, Eigen::Index r) {
  const Eigen::Index p = H.rows();
  Eigen::VectorXd scale(p);
  for (Eigen::Index j = 0; j < p; ++j) scale(j) = H(j, j) > 0.0 ? 1.0 / std::sqrt(H(j, j)) : 1.0;
  const Eigen::MatrixXd Hs = scale.asDiagonal() * H * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (Hs + Hs.transpose()));
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(p, p);
  for (Eigen::Index k = p - r; k < p; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (lambda > 0.0) inverse += eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose() / lambda;
  }
  return scale.asDiagonal() * inverse * scale.asDiagonal();
}

physical::Certificate certificate_of(const shared::ConeCertificate& c, double theta_scale, bool convex) {
  physical::Certificate out;
  out.stationarity = c.stationarity;
  out.primal_min_eig = c.primal_min_eig / theta_scale;
  out.dual_min_eig = c.dual_min_eig;
  out.complementarity = c.complementarity;
  out.duality_gap = convex ? std::abs(c.complementarity) : std::numeric_limits<double>::quiet_NaN();
  return out;
}

// Every stride-th sample of `kin` (and of the weights `counts` when given).
Kinematics every_nth(const Kinematics& kin, Eigen::Index stride, const std::vector<double>& counts,
                     std::vector<double>& sub_counts) {
  Kinematics out;
  const Eigen::Index n = (kin.samples() + stride - 1) / stride;
  const auto columns = Eigen::seqN(0, n, stride);
  out.wrench = kin.wrench(Eigen::all, columns);
  out.specific_force = kin.specific_force(Eigen::all, columns);
  out.omega = kin.omega(Eigen::all, columns);
  out.alpha = kin.alpha(Eigen::all, columns);
  out.moving = kin.moving;
  out.rotating = kin.rotating;
  out.sign = kin.sign;
  sub_counts.clear();
  if (!counts.empty()) {
    for (Eigen::Index k = 0; k < n; ++k) sub_counts.push_back(counts[static_cast<std::size_t>(k * stride)]);
  }
  return out;
}

}  // namespace

Fit fit_payload(const Kinematics& kin, const IdentifyRequest& request, const NoiseCovariances& noise,
                const std::vector<double>& counts, bool reported, bool frequency) {
  Fit out;
  out.layout.moving = kin.moving;
  const ParameterLayout& layout = out.layout;
  const int p = layout.size();
  const std::vector<std::string> names = layout.names();
  const shared::ConeLayout cone = cone_layout(layout);
  const Whitening white = whitening(noise);

  const TriangularFactor factor = least_squares_factor(kin, layout, white, counts, frequency);
  const double theta_scale = std::ldexp(1.0, factor.exponent_a() - factor.exponent_b());
  const double unscale2 = std::ldexp(1.0, 2 * factor.exponent_b());
  const Eigen::MatrixXd R11 = factor.R11();
  const Eigen::VectorXd r12 = factor.R12().col(0);
  const double rho2 = factor.R22().squaredNorm();
  const Eigen::Index rows = factor.rows();
  const double cutoff = rank_cutoff(request.rank_tolerance.value_or(-1.0), rows, p);
  out.identifiability = physical::detail::identifiability(R11, names, cutoff);
  const Eigen::Index rank = out.identifiability.rank;

  // The unconstrained least-squares fit, in the factor's scaled units (phi_s = theta_scale phi).
  std::vector<int> all(static_cast<std::size_t>(p));
  for (int j = 0; j < p; ++j) all[static_cast<std::size_t>(j)] = j;
  const Eigen::VectorXd phi_ls_s = minimum_norm(R11, r12, all, cutoff);
  out.phi_ls = phi_ls_s / theta_scale;
  // The sandwich of least squares at phi: (X^T X)^+ (sum_k X_k^T r_k r_k^T X_k) (X^T X)^+ in the
  // whitened units, X^T X = R11^T R11 2^(2 ea); HC1's factor rows / (rows - rank). Robust to force and
  // torque noise of different sizes without weights.
  const Eigen::MatrixXd Hplus_ls =
      pseudo_inverse(R11.transpose() * R11, rank) * std::ldexp(1.0, -2 * factor.exponent_a());
  const auto sandwich = [&](const Eigen::VectorXd& phi_at) {
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(p, p);
    Eigen::MatrixXd X(6, p);
    for (Eigen::Index k = 0; k < kin.samples(); ++k) {
      const double count = counts.empty() ? 1.0 : counts[static_cast<std::size_t>(k)];
      if (count == 0.0) continue;
      // A count repeats the sample's score; a reliability weight scales its residual (squared).
      const double weight = frequency ? count : count * count;
      sample_regressor(kin, k, layout, X);
      Eigen::Matrix<double, 6, 1> r = X * phi_at - kin.wrench.col(k);
      white.apply(X);
      white.apply(r);
      const Eigen::VectorXd score = X.transpose() * r;
      S.noalias() += weight * score * score.transpose();
    }
    const double n = static_cast<double>(rows);
    return Eigen::MatrixXd(Hplus_ls * S * Hplus_ls * (n / std::max(n - static_cast<double>(rank), 1.0)));
  };
  if (reported) out.mass_ls_se = std::sqrt(std::max(sandwich(out.phi_ls)(0, 0), 0.0));

  // The solver's coordinates: L from the columns of the mass and the first moment.
  double first = 0.0;
  for (int j = 1; j <= 3; ++j) first += R11.col(j).squaredNorm();
  first = std::sqrt(first / 3.0);
  out.length = R11.col(0).norm() / first;
  if (!std::isfinite(out.length) || !(out.length > 0.0)) out.length = 1.0;
  const Eigen::MatrixXd M = coordinate_map(layout, out.length, false);
  const Eigen::MatrixXd Minv = coordinate_map(layout, out.length, true);
  const double total = r12.squaredNorm() + rho2;
  shared::LinearCriterion ls(R11 * M, r12, rho2, total > 0.0 ? total : 1.0);
  if (rank < p && layout.moving && request.consistent) {
    // Undetermined directions: a ridge bounds the barrier problems (LinearCriterion::set_ridge).
    ls.set_ridge(kRidge * (R11 * M).colwise().squaredNorm().mean() * 2.0 / ls.f0());
  }

  Eigen::VectorXd theta_s = Minv * phi_ls_s;  // scaled units
  const bool m_determined = out.identifiability.determined[0];
  if (request.consistent) {
    if (!layout.moving) {
      // m >= 0: the unconstrained fit where its mass is >= 0, else the fit with m = 0 (the one
      // active set of a convex quadratic with one bound).
      if (phi_ls_s(0) < 0.0 && m_determined) {
        std::vector<int> rest(all.begin() + 1, all.end());
        theta_s = minimum_norm(R11, r12, rest, cutoff);
        out.active = true;
      }
    } else if (!shared::strictly_feasible(cone, theta_s)) {
      const shared::SolveResult solved =
          shared::solve_constrained(ls, cone, shared::pushed_inside(cone, theta_s, kStartInside), request.max_iterations);
      theta_s = solved.theta;
      out.iterations += solved.iterations;
      out.converged = solved.converged;
      out.failure = solved.message;
    }
  }
  out.criterion = ls.residual_squares(theta_s) * unscale2;
  if (reported && request.consistent && request.criterion == Criterion::LeastSquares) {
    out.certificate = certificate_of(shared::kkt_certificate(ls, cone, theta_s), theta_scale, true);
  }
  Eigen::VectorXd phi = M * theta_s / theta_scale;

  if (request.criterion == Criterion::ErrorsInVariables && out.converged) {
    // Errors in variables, in physical units, from the least-squares fit (not convex: as the
    // hexapod's physical fit, two starts and the lower local minimum).
    EivCriterion eiv(kin, layout, M, noise.wrench, noise.pose, request.threads, counts);
    eiv.set_reliability_weights(!frequency);
    eiv.set_keep_scores(reported);  // the sandwich's scores from the minimizer's last Newton pass
    const Eigen::VectorXd theta_c = Minv * phi;          // the (constrained) least-squares fit
    const Eigen::VectorXd theta_free = Minv * out.phi_ls;  // the unconstrained one
    double f_start = 0.0;
    const Eigen::VectorXd start = request.consistent && !shared::strictly_feasible(cone, theta_c)
                                      ? shared::pushed_inside(cone, theta_c, kStartInside)
                                      : theta_c;
    if (!eiv.evaluate_phi(M * start, 0, f_start, nullptr, nullptr)) {
      throw SignalError("the noise model makes the errors-in-variables weight singular: give the wrench's noise "
                        "(`noise_std_wrench` or `rest_rows`)", Code::NoiseModel);
    }
    // Noise-free data: the least-squares fit's residuals are at rounding level against the noise
    // model, so the criterion is 0 there, its minimum; Newton's method from there would chase the
    // rounding (the normalization f0 is rounding itself). The estimate is least squares'.
    if (f_start <= kExactCriterion * static_cast<double>(6 * kin.samples())) {
      out.criterion = f_start;
      if (reported) {
        out.covariance = sandwich(phi);
        if (request.consistent) out.certificate = certificate_of(shared::kkt_certificate(ls, cone, theta_s), theta_scale, true);
      }
    } else {
      eiv.set_normalization(f_start);
      std::optional<shared::SolveResult> best;
      auto consider = [&](const shared::SolveResult& r, bool usable) {
        out.iterations += r.iterations;
        if (!usable) return;
        if (!best || (r.converged && !best->converged) || (r.converged == best->converged && r.f < best->f)) best = r;
      };
      const auto budget = [&] { return std::max(request.max_iterations - out.iterations, 1); };
      // The unconstrained fit's start: least squares', or on a long log the errors-in-variables fit
      // to a subsample from there (its Newton steps are not counted in `iterations`).
      Eigen::VectorXd free_start = theta_free;
      if (const Eigen::Index stride = kin.samples() / kCoarseSamples; stride >= kCoarseStride) {
        std::vector<double> sub_counts;
        const Kinematics sub = every_nth(kin, stride, counts, sub_counts);
        EivCriterion coarse(sub, layout, M, noise.wrench, noise.pose, request.threads, sub_counts);
        double f_coarse = 0.0;
        if (coarse.evaluate_phi(M * theta_free, 0, f_coarse, nullptr, nullptr)) {
          coarse.set_normalization(f_coarse);
          const shared::SolveResult r = shared::solve_unconstrained(coarse, theta_free, request.max_iterations);
          if (r.converged && r.theta.allFinite()) free_start = r.theta;
        }
      }
      if (!request.consistent) {
        consider(shared::solve_unconstrained(eiv, free_start, budget()), true);
      } else {
        const shared::SolveResult free = shared::solve_unconstrained(eiv, free_start, budget());
        const bool inside = free.converged && shared::strictly_feasible(cone, free.theta);
        consider(free, inside);
        if (!inside || !shared::strictly_feasible(cone, theta_free)) {
          consider(shared::solve_constrained(eiv, cone, start, budget()), true);
          if (free.converged && !inside && free.theta.allFinite()) {
            int steps = 0;
            const std::optional<shared::SolveResult> face = shared::solve_on_face(eiv, cone, free.theta, budget(), &steps);
            out.iterations += steps;
            if (face) {
              consider(*face, true);
            } else {
              consider(shared::solve_constrained(eiv, cone, shared::pushed_inside(cone, free.theta, kStartInside), budget()),
                       true);
            }
          }
        }
      }
      phi = M * best->theta;
      out.converged = best->converged;
      out.failure = best->message;
      if (reported && request.consistent) {
        out.certificate = certificate_of(shared::kkt_certificate(eiv, cone, best->theta), 1.0, false);
      }
      // The sandwich of an M-estimator when reported: H^+ S H^+, H half the Hessian, S the sum of
      // the samples' half-gradient outer products (the same pass gives F).
      double f = 0.0;
      Eigen::VectorXd g;
      Eigen::MatrixXd H, S;
      if (reported && eiv.evaluate_phi(phi, 2, f, &g, &H, &S)) {
        const Eigen::MatrixXd Hplus = pseudo_inverse(0.5 * H, rank);
        const double n = static_cast<double>(kin.samples());
        out.covariance = Hplus * S * Hplus * (6.0 * n / std::max(6.0 * n - static_cast<double>(rank), 1.0));
      } else {
        eiv.evaluate_phi(phi, 0, f, nullptr, nullptr);
      }
      out.criterion = f;
    }
  } else if (reported) {
    out.covariance = sandwich(phi);
  }
  out.phi = phi;

  // Where the estimate lies in the cone.
  if (layout.moving) {
    const Eigen::VectorXd theta = Minv * phi;
    const Eigen::Vector4d d =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(shared::body_matrix(theta, 0), Eigen::EigenvaluesOnly).eigenvalues();
    out.pseudo_min = d(0);
    out.active = request.consistent && d(0) <= kActive * d(3);
  } else {
    out.pseudo_min = phi(0);
    out.active = request.consistent && m_determined && phi(0) <= kActive * std::abs(out.phi_ls(0));
  }
  if (reported) {
    out.residuals.resize(kin.samples(), 6);
    Eigen::MatrixXd X(6, p);
    for (Eigen::Index k = 0; k < kin.samples(); ++k) {
      sample_regressor(kin, k, layout, X);
      out.residuals.row(k) = (X * phi - kin.wrench.col(k)).transpose();
    }
  }
  return out;
}

namespace {

// Reweightings of the robust fit at most, and when they stop (as hexapod identify --physical's).
constexpr int kReweightings = 50;
constexpr double kSettled = 1e-8;

// Least squares' whitening of a sample's residual wrench for the robust weights: the wrench noise's
// (as the fit weighs it) or, without one, each axis' robust scale (robust_spread) in the residuals of
// `phi` over the counted samples, so that forces (N) and torques (N m) count alike.
Eigen::Matrix<double, 6, 6> residual_whitening(const Kinematics& kin, const ParameterLayout& layout,
                                               const NoiseCovariances& noise, const Eigen::VectorXd& phi,
                                               const std::vector<double>& counts) {
  if (noise.wrench.size()) {
    const Whitening white = whitening(noise);
    return white.L.triangularView<Eigen::Lower>().solve(Eigen::Matrix<double, 6, 6>::Identity());
  }
  std::array<std::vector<double>, 6> axis;
  Eigen::MatrixXd X(6, layout.size());
  for (Eigen::Index k = 0; k < kin.samples(); ++k) {
    if (!counts.empty() && counts[static_cast<std::size_t>(k)] == 0.0) continue;
    sample_regressor(kin, k, layout, X);
    const Eigen::Matrix<double, 6, 1> r = X * phi - kin.wrench.col(k);
    for (int a = 0; a < 6; ++a) axis[static_cast<std::size_t>(a)].push_back(r(a));
  }
  Eigen::Matrix<double, 6, 1> s;
  for (int a = 0; a < 6; ++a) {
    std::vector<double>& v = axis[static_cast<std::size_t>(a)];
    if (v.empty()) {
      s(a) = 0.0;
      continue;
    }
    s(a) = spdfit::detail::robust_spread(v);
  }
  // An axis without spread (noise-free data, a constant channel) is scaled as the largest one.
  const double largest = s.maxCoeff();
  for (int a = 0; a < 6; ++a) s(a) = s(a) > 1e-12 * largest ? s(a) : (largest > 0.0 ? largest : 1.0);
  return s.cwiseInverse().asDiagonal();
}

}  // namespace

RobustPayloadFit robust_fit_payload(const Kinematics& kin, const IdentifyRequest& request, const NoiseCovariances& noise,
                                    const std::vector<double>& counts, bool reported, const Eigen::VectorXd* start,
                                    double start_scale) {
  IdentifyRequest plain = request;
  plain.robust = RobustLoss::None;
  plain.robust_tuning.reset();
  const Eigen::Index m = kin.samples();
  ParameterLayout layout;
  layout.moving = kin.moving;
  const int p = layout.size();
  const double median_chi = spdfit::detail::chi_median(6);
  RobustPayloadFit out;
  Eigen::VectorXd phi;
  if (start) {
    phi = *start;
    out.scale = start_scale;
  } else {
    phi = fit_payload(kin, plain, noise, counts, false).phi;  // counts: a replicate's (frequencies)
  }
  const Eigen::Matrix<double, 6, 6> Linv = residual_whitening(kin, layout, noise, phi, counts);
  std::optional<EivCriterion> eiv;
  if (request.criterion == Criterion::ErrorsInVariables) {
    eiv.emplace(kin, layout, Eigen::MatrixXd::Identity(p, p), noise.wrench, noise.pose, request.threads);
  }
  const auto norms = [&](const Eigen::VectorXd& at) {
    if (eiv) return eiv->sample_norms(at);
    Eigen::VectorXd u(m);
    Eigen::MatrixXd X(6, p);
    for (Eigen::Index k = 0; k < m; ++k) {
      sample_regressor(kin, k, layout, X);
      u(k) = (Linv * (X * at - kin.wrench.col(k))).norm();
    }
    return u;
  };
  std::vector<double> weights(static_cast<std::size_t>(m), 1.0);
  const Eigen::VectorXd counted = counts.empty() ? Eigen::VectorXd() : Eigen::Map<const Eigen::VectorXd>(
                                                                           counts.data(), static_cast<Eigen::Index>(counts.size()));
  std::vector<double> bracket;  // median_near's scratch
  // One loss's reweightings from phi; Huber re-estimates the scale, Tukey keeps the one it is given.
  const auto reweight = [&](RobustLoss loss, double k, int& iterations) {
    bool settled = false;
    for (int it = 1; it <= kReweightings && !settled; ++it) {
      const Eigen::VectorXd u = norms(phi);
      if (!u.allFinite()) {
        throw SignalError("the errors-in-variables weight of some sample is singular at the robust fit's estimate",
                          Code::NoiseModel);
      }
      if (loss == RobustLoss::Huber) {  // the scale of the samples drawn, as the generic robust fit's
        const double next = spdfit::detail::median_near(u, counted, out.scale * median_chi, bracket);
        if (!std::isnan(next)) out.scale = next / median_chi;
      }
      out.weights = spdfit::detail::robust_weights(loss, u, out.scale, k);
      for (Eigen::Index i = 0; i < m; ++i) {
        weights[static_cast<std::size_t>(i)] = out.weights(i) * (counts.empty() ? 1.0 : counts[static_cast<std::size_t>(i)]);
      }
      const Eigen::VectorXd next = fit_payload(kin, plain, noise, weights, false, false).phi;
      ++iterations;
      settled = (next - phi).norm() <= kSettled * std::max(next.norm(), std::numeric_limits<double>::min()) ||
                out.scale == 0.0;
      phi = next;
    }
    return settled;
  };
  const RobustLoss loss = request.robust;
  const double k = request.robust_tuning.value_or(spdfit::detail::robust_tuning(loss, 6));
  out.tuning = k;
  if (loss == RobustLoss::Tukey && !start) {
    // Huber's fit and scale first: Tukey's weights from a fit that gross errors still lean on would
    // give the good samples weight 0.
    int huber_iterations = 0;
    reweight(RobustLoss::Huber, spdfit::detail::robust_tuning(RobustLoss::Huber, 6), huber_iterations);
    out.iterations += huber_iterations;
  }
  int iterations = 0;
  out.converged = reweight(loss, k, iterations);
  out.iterations += iterations;
  out.fit = fit_payload(kin, plain, noise, weights, reported, false);
  return out;
}

}  // namespace spdfit::payload::detail
