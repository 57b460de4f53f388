#include "hexapod/physical_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace spdfit::hexapod::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
const double kRoot2 = std::sqrt(2.0);

// Sufficient decrease of the backtracking line search (Armijo), and the smallest step tried.
constexpr double kArmijo = 1e-4;
constexpr double kMinStep = 1e-12;
// The barrier weight: the first stage's mu is kInitialBarrier f(theta0) / nu (nu = 4 + the strut
// masses, the barrier's parameter), each later stage's kBarrierDecrease times the previous one's,
// down to the last stage's kFinalBarrier / nu, at which the barrier moves the minimizer by about
// kFinalBarrier relative to f0 (nu mu bounds the criterion's excess at a barrier centre for a
// convex criterion): below what the data resolve, and near the criterion's rounding level.
constexpr double kInitialBarrier = 1e-2;
constexpr double kBarrierDecrease = 0.05;
constexpr double kFinalBarrier = 1e-14;
// A stage ends when the squared Newton decrement is below kCentering mu (the centring rule of
// barrier methods, for F / mu); the last one when it is below kFinalDecrement (in units of f0:
// steps of relative size about 1e-13) or at rounding level.
constexpr double kCentering = 0.1;
constexpr double kFinalDecrement = 1e-26;
// The rounding error of a computed criterion or barrier value, in units of eps times its size.
constexpr double kRoundingMultiple = 64.0;
// Steps taken with the predicted decrease below the rounding level before a stage counts as done.
constexpr int kRoundingSteps = 2;
// Newton steps of a face solve tried after a barrier stage, and the fraction of P's largest
// eigenvalue below which an eigenvalue counts as leaving the face (as in solve_on_face).
constexpr int kPolishSteps = 12;
constexpr double kFaceGuess = 1e-3;
// Strictly inside the cone: P's eigenvalues and the strut masses above this fraction of P's largest
// eigenvalue (the barrier and its Hessian stay finite and resolvable).
constexpr double kInteriorFraction = 1e-13;
// No minimizer: the unconstrained iterates grew beyond this multiple of the start's size.
constexpr double kUnboundedRatio = 1e8;
// An eigenvalue of P (or a strut mass) below this fraction of P's largest counts as on the
// boundary (the barrier leaves active ones at about mu / multiplier, far below it).
constexpr double kActiveFraction = 1e-6;

// The basis matrix E_a of the symmetric 4 x 4 matrices (physical_model.hpp).
Eigen::Matrix4d basis(int a) {
  Eigen::Matrix4d E = Eigen::Matrix4d::Zero();
  const int i = kPairs[a][0], j = kPairs[a][1];
  if (i == j) {
    E(i, i) = 1.0;
  } else {
    E(i, j) = E(j, i) = 1.0 / kRoot2;
  }
  return E;
}

// <S, E_a> for a symmetric S.
double coordinate(const Eigen::Matrix4d& S, int a) {
  const int i = kPairs[a][0], j = kPairs[a][1];
  return i == j ? S(i, i) : kRoot2 * S(i, j);
}

Matrix6d sym(const Matrix6d& M) { return 0.5 * (M + M.transpose()); }

double inner(const Matrix6d& A, const Matrix6d& B) { return A.cwiseProduct(B).sum(); }

// The log-det barrier -log det P - sum log s and its derivatives; false outside the open cone.
struct Barrier {
  double phi = 0.0;
  ParamVector g;
  ParamMatrix H;
};

bool barrier(const PhysicalModel& model, const ParamVector& theta, int order, Barrier& out) {
  const int p = model.parameters;
  const Eigen::LLT<Eigen::Matrix4d> llt(scaled_pseudo_inertia(theta));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector4d diagonal = llt.matrixLLT().diagonal();
  if (!(diagonal.minCoeff() > 0.0)) return false;
  out.phi = -2.0 * diagonal.array().log().sum();
  for (int a = kPayloadParameters; a < p; ++a) {
    if (!(theta(a) > 0.0)) return false;
    out.phi -= std::log(theta(a));
  }
  if (!std::isfinite(out.phi)) return false;
  if (order < 1) return true;
  const Eigen::Matrix4d Pinv = llt.solve(Eigen::Matrix4d::Identity());
  out.g.setZero(p);
  for (int a = 0; a < kPayloadParameters; ++a) out.g(a) = -coordinate(Pinv, a);
  for (int a = kPayloadParameters; a < p; ++a) out.g(a) = -1.0 / theta(a);
  if (order < 2) return true;
  out.H.setZero(p, p);
  for (int a = 0; a < kPayloadParameters; ++a) {
    const Eigen::Matrix4d B = Pinv * basis(a) * Pinv;  // the Hessian D -> P^-1 D P^-1 applied to E_a
    for (int b = 0; b < kPayloadParameters; ++b) out.H(b, a) = coordinate(B, b);
  }
  for (int a = kPayloadParameters; a < p; ++a) out.H(a, a) = 1.0 / (theta(a) * theta(a));
  out.H = 0.5 * (out.H + out.H.transpose()).eval();
  return true;
}

// f + mu phi with gradient and Hessian (phi only when mu > 0 or the cone is enforced).
struct Merit {
  double value = 0.0, rounding = 0.0;
  ParamVector g;
  ParamMatrix H;
};

bool merit(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta, double mu,
           bool constrained, int order, Merit& out, Evaluation& ev) {
  if (!evaluate(data, model, theta, order, ev)) return false;
  out.value = ev.f;
  out.rounding = kRoundingMultiple * kEps * std::abs(ev.f);
  if (order >= 1) out.g = ev.g;
  if (order >= 2) out.H = ev.H;
  if (!constrained) return true;
  Barrier b;
  if (!barrier(model, theta, order, b)) return false;
  if (mu > 0.0) {
    out.value += mu * b.phi;
    out.rounding += kRoundingMultiple * kEps * std::abs(mu * b.phi);
    if (order >= 1) out.g += mu * b.g;
    if (order >= 2) out.H += mu * b.H;
  }
  return std::isfinite(out.value);
}

enum class StageEnd { Converged, Budget, Failed };

// Newton's method on f + mu phi from theta (feasible when constrained). Ends Converged when the
// squared decrement is below `tolerance` or at the criterion's rounding level (no step can
// decrease it measurably), Budget after the iteration budget, Failed when the merit cannot be
// evaluated at theta or the iterates run off to infinity.
StageEnd newton(const PhysicalData& data, const PhysicalModel& model, double mu, bool constrained, double tolerance,
                int max_iterations, int& iterations, ParamVector& theta, double* last_decrement = nullptr) {
  const int p = model.parameters;
  Merit cur, trial;
  Evaluation ev;
  const double start_norm = std::max(theta.norm(), std::numeric_limits<double>::min());
  Eigen::LLT<ParamMatrix> llt(p);
  int at_rounding = 0;  // consecutive steps whose predicted decrease was below the merit's rounding
  for (;;) {
    if (!merit(data, model, theta, mu, constrained, 2, cur, ev)) return StageEnd::Failed;
    // Levenberg-Marquardt: the smallest shift in {0, 1e-12, 1e-11, ...} times the Hessian's
    // diagonal scale that makes it positive definite (a descent direction far from a minimum).
    const double scale = std::max(cur.H.diagonal().cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
    double shift = 0.0;
    ParamMatrix H = cur.H;
    for (;;) {
      llt.compute(H);
      if (llt.info() == Eigen::Success && (llt.matrixLLT().diagonal().array() > 0.0).all()) break;
      shift = shift == 0.0 ? 1e-12 * scale : 10.0 * shift;
      if (!(shift < 1e12 * scale)) return StageEnd::Failed;
      H = cur.H;
      H.diagonal().array() += shift;
    }
    const ParamVector step = -llt.solve(cur.g);
    const double decrement = -cur.g.dot(step);
    if (last_decrement) *last_decrement = decrement;
    if (!std::isfinite(decrement)) return StageEnd::Failed;
    if (decrement <= tolerance) return StageEnd::Converged;
    // Newton's decrement cannot fall below the rounding of the computed gradient: once the
    // predicted decrease is below the merit's own rounding for kRoundingSteps steps in a row
    // (quadratic convergence has then had its steps), the minimizer is found to working accuracy.
    at_rounding = decrement <= cur.rounding ? at_rounding + 1 : 0;
    if (at_rounding > kRoundingSteps) return StageEnd::Converged;
    if (iterations >= max_iterations) return StageEnd::Budget;
    ++iterations;
    bool accepted = false;
    for (double alpha = 1.0; alpha >= kMinStep; alpha *= 0.5) {
      const ParamVector next = theta + alpha * step;
      if (constrained && !strictly_feasible(model, next)) continue;
      Evaluation trial_ev;
      if (!merit(data, model, next, mu, constrained, 0, trial, trial_ev)) continue;
      const bool decreases = trial.value <= cur.value - kArmijo * alpha * decrement;
      // Below the merit's resolution the decrease cannot be seen: take the step unless the merit
      // rose beyond its rounding, and let the next gradient judge it.
      const bool at_rounding = alpha * decrement <= cur.rounding && trial.value <= cur.value + cur.rounding;
      if (decreases || at_rounding) {
        theta = next;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No step decreases the merit measurably: the decrement is at the rounding level.
      return decrement <= 1e3 * cur.rounding ? StageEnd::Converged : StageEnd::Failed;
    }
    if (!constrained && theta.norm() > kUnboundedRatio * start_norm) return StageEnd::Failed;
  }
}

}  // namespace

PhysicalData physical_data(const TriangularFactor& factor, const PhysicalModel& model, PhysicalCriterion criterion,
                           const Eigen::MatrixXd& noise_a, const Eigen::MatrixXd& noise_b) {
  PhysicalData d;
  d.criterion = criterion;
  d.R11 = factor.R11();
  d.R12 = factor.R12();
  d.R22 = factor.R22();
  d.E22 = d.R22.transpose() * d.R22;
  d.theta_scale = std::ldexp(1.0, factor.exponent_a() - factor.exponent_b());
  const double scale_a = std::ldexp(1.0, -2 * factor.exponent_a());
  const double scale_b = std::ldexp(1.0, -2 * factor.exponent_b());
  d.noise_a = noise_a.size() ? Matrix6d(noise_a * scale_a) : Matrix6d(Matrix6d::Identity() * scale_a);
  d.noise_b = noise_b.size() ? Matrix6d(noise_b * scale_b) : Matrix6d(Matrix6d::Identity() * scale_b);
  d.M0 = d.theta_scale * model.M0;
  for (int a = 0; a < model.parameters; ++a) {
    const Matrix6d& D = model.D[static_cast<std::size_t>(a)];
    d.X.push_back(d.R11 * D);
    d.Q.push_back(d.R11.transpose() * d.X.back());
    d.SD.push_back(d.noise_a * D);
  }
  return d;
}

double raw_criterion(const PhysicalData& data, const Matrix6d& M) {
  const Matrix6d Rm = data.R11 * M - data.R12;
  if (data.criterion == PhysicalCriterion::LeastSquares) return Rm.squaredNorm() + data.R22.squaredNorm();
  const Matrix6d W = sym(M * data.noise_a * M + data.noise_b);
  const Eigen::LLT<Matrix6d> llt(W);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  const Matrix6d E = Rm.transpose() * Rm + data.E22;
  return inner(E, llt.solve(Matrix6d::Identity()));
}

bool set_normalization(PhysicalData& data, const PhysicalModel& model, const ParamVector& theta_start) {
  if (data.criterion == PhysicalCriterion::LeastSquares) {
    data.f0 = data.R12.squaredNorm() + data.R22.squaredNorm();
  } else {
    Matrix6d M = data.M0;
    for (int a = 0; a < model.parameters; ++a) M += theta_start(a) * model.D[static_cast<std::size_t>(a)];
    const Eigen::LLT<Matrix6d> llt(sym(M * data.noise_a * M + data.noise_b));
    if (llt.info() != Eigen::Success) return false;
    data.f0 = inner(data.R12.transpose() * data.R12 + data.E22, llt.solve(Matrix6d::Identity()));
  }
  if (!(data.f0 > 0.0) || !std::isfinite(data.f0)) data.f0 = 1.0;  // B = 0: nothing to scale by
  return true;
}

bool evaluate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta, int order,
              Evaluation& out) {
  const int p = model.parameters;
  Matrix6d M = data.M0;
  for (int a = 0; a < p; ++a) M += theta(a) * model.D[static_cast<std::size_t>(a)];
  M = sym(M);
  const Matrix6d Rm = data.R11 * M - data.R12;
  const double inv_f0 = 1.0 / data.f0;

  if (data.criterion == PhysicalCriterion::LeastSquares) {
    out.f = (Rm.squaredNorm() + data.R22.squaredNorm()) * inv_f0;
    if (order >= 1) {
      out.g.resize(p);
      for (int a = 0; a < p; ++a) out.g(a) = 2.0 * inv_f0 * inner(Rm, data.X[static_cast<std::size_t>(a)]);
    }
    if (order >= 2) {
      out.H.resize(p, p);
      for (int a = 0; a < p; ++a)
        for (int b = 0; b <= a; ++b) {
          out.H(a, b) = out.H(b, a) =
              2.0 * inv_f0 * inner(data.X[static_cast<std::size_t>(a)], data.X[static_cast<std::size_t>(b)]);
        }
    }
    return std::isfinite(out.f);
  }

  // Errors in variables: f = <E, K>, E = Rm^T Rm + R22^T R22, K = W^-1, W = M Sigma_A M + Sigma_B.
  const Matrix6d SM = data.noise_a * M;
  const Eigen::LLT<Matrix6d> llt(sym(M * SM + data.noise_b));
  if (llt.info() != Eigen::Success) return false;
  const Matrix6d K = llt.solve(Matrix6d::Identity());
  const Matrix6d E = Rm.transpose() * Rm + data.E22;
  out.f = inner(E, K) * inv_f0;
  if (!std::isfinite(out.f)) return false;
  if (order < 1) return true;
  // Gradient over symmetric dM: Gamma = 2 sym(R11^T Rm K - Sigma_A M F), F = K E K.
  const Matrix6d KE = K * E;
  const Matrix6d F = sym(KE * K);
  const Matrix6d NRm = data.R11.transpose() * Rm;
  const Matrix6d Gamma = 2.0 * inv_f0 * sym(NRm * K - SM * F);
  out.g.resize(p);
  for (int a = 0; a < p; ++a) out.g(a) = inner(Gamma, model.D[static_cast<std::size_t>(a)]);
  if (order < 2) return true;
  // Hessian column a: the derivative of Gamma along D_a, with dW = D Sigma_A M + M Sigma_A D,
  // dK = -K dW K, dE = (R11 D)^T Rm + Rm^T R11 D, dF = dK E K + K dE K + K E dK.
  out.H.resize(p, p);
  const Matrix6d EK = KE.transpose();
  for (int a = 0; a < p; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const Matrix6d& D = model.D[ua];
    const Matrix6d Y = D * SM;
    const Matrix6d dK = -K * (Y + Y.transpose()) * K;
    const Matrix6d XR = data.X[ua].transpose() * Rm;
    const Matrix6d dE = XR + XR.transpose();
    const Matrix6d dF = dK * EK + K * dE * K + KE * dK;
    const Matrix6d dGamma = 2.0 * inv_f0 * sym(data.Q[ua] * K + NRm * dK - data.SD[ua] * F - SM * dF);
    for (int b = 0; b < p; ++b) out.H(b, a) = inner(dGamma, model.D[static_cast<std::size_t>(b)]);
  }
  out.H = 0.5 * (out.H + out.H.transpose()).eval();
  return true;
}

ParamVector unconstrained_least_squares(const PhysicalData& data, const PhysicalModel& model, double cutoff,
                                        Eigen::Index* rank, Eigen::MatrixXd* null_space) {
  const int p = model.parameters;
  Eigen::Matrix<double, 36, Eigen::Dynamic, Eigen::ColMajor, 36, kMaxPhysicalParameters> Phi(36, p);
  const Matrix6d target = data.R12 - data.R11 * data.M0;
  ParamVector column_scale(p);
  for (int a = 0; a < p; ++a) {
    const double norm = data.X[static_cast<std::size_t>(a)].norm();
    column_scale(a) = norm > 0.0 ? 1.0 / norm : 1.0;
    Phi.col(a) = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(data.X[static_cast<std::size_t>(a)].data()) *
                 column_scale(a);
  }
  const Eigen::JacobiSVD<decltype(Phi)> svd(Phi, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& s = svd.singularValues();
  Eigen::Index r = 0;
  while (r < p && s(r) > cutoff * s(0)) ++r;
  if (rank) *rank = r;
  if (null_space) *null_space = column_scale.asDiagonal() * svd.matrixV().rightCols(p - r);
  const Eigen::Matrix<double, 36, 1> y = Eigen::Map<const Eigen::Matrix<double, 36, 1>>(target.data());
  ParamVector coefficients = ParamVector::Zero(p);
  const ParamVector Uty = svd.matrixU().leftCols(r).transpose() * y;
  for (Eigen::Index k = 0; k < r; ++k) coefficients += svd.matrixV().col(k) * (Uty(k) / s(k));
  return column_scale.cwiseProduct(coefficients);
}

bool strictly_feasible(const PhysicalModel& model, const ParamVector& theta) {
  // A Cholesky factorization succeeds on a semidefinite P with rounding-level pivots; the barrier
  // needs P clearly inside.
  const Eigen::Vector4d d =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(scaled_pseudo_inertia(theta), Eigen::EigenvaluesOnly).eigenvalues();
  const double floor = kInteriorFraction * d.maxCoeff();
  if (!(d.minCoeff() > floor) || !std::isfinite(d.maxCoeff())) return false;
  for (int a = kPayloadParameters; a < model.parameters; ++a)
    if (!(theta(a) > floor)) return false;
  return true;
}

ParamVector pushed_inside(const PhysicalModel& model, const ParamVector& theta, double fraction) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(scaled_pseudo_inertia(theta));
  const Eigen::Vector4d d = solver.eigenvalues();
  const double floor = fraction * std::max(d.maxCoeff(), std::numeric_limits<double>::min());
  const Eigen::Matrix4d P =
      solver.eigenvectors() * d.cwiseMax(floor).asDiagonal() * solver.eigenvectors().transpose();
  ParamVector out = theta;
  set_pseudo_inertia(P, out);
  for (int a = kPayloadParameters; a < model.parameters; ++a) out(a) = std::max(out(a), floor);
  return out;
}

SolveResult solve_constrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                              int max_iterations) {
  SolveResult out;
  out.theta = theta0;
  const double nu = 4.0 + (model.parameters - kPayloadParameters);
  Evaluation ev;
  if (!strictly_feasible(model, theta0) || !evaluate(data, model, theta0, 0, ev)) {
    out.message = "the start is not strictly inside the cone of physical parameters";
    return out;
  }
  const double mu_final = kFinalBarrier / nu;
  double mu = std::max(kInitialBarrier * ev.f / nu, mu_final);
  bool tried[5] = {false, false, false, false, false};  // face solves tried, by rank
  for (;;) {
    const bool last = mu <= mu_final;
    const StageEnd end = newton(data, model, mu, true, last ? kFinalDecrement : kCentering * mu, max_iterations,
                                out.iterations, out.theta);
    if (end == StageEnd::Failed) {
      out.message = "Newton's method on the barrier problem found no descent (the criterion could not be "
                    "evaluated or decreased)";
      break;
    }
    if (end == StageEnd::Budget) {
      out.message = "stopped after `max_iterations` = " + std::to_string(max_iterations) + " Newton steps";
      break;
    }
    if (last) {
      out.converged = true;
      break;
    }
    // The face the iterate points to, solved once per rank: quadratic convergence to a minimizer
    // on the boundary, where the path would need many more stages.
    const Eigen::Vector4d d =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(scaled_pseudo_inertia(out.theta), Eigen::EigenvaluesOnly)
            .eigenvalues();
    const auto rank = static_cast<int>((d.array() > kFaceGuess * d.maxCoeff()).count());
    if (!tried[rank]) {
      tried[rank] = true;
      int steps = 0;
      const std::optional<SolveResult> face =
          solve_on_face(data, model, out.theta, std::min(kPolishSteps, max_iterations - out.iterations), &steps);
      out.iterations += steps;
      if (face) {
        out.theta = face->theta;
        out.converged = true;
        break;
      }
    }
    mu = std::max(mu * kBarrierDecrease, mu_final);
  }
  evaluate(data, model, out.theta, 0, ev);
  out.f = ev.f;
  return out;
}

SolveResult solve_unconstrained(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta0,
                                int max_iterations) {
  SolveResult out;
  out.theta = theta0;
  const StageEnd end = newton(data, model, 0.0, false, kFinalDecrement, max_iterations, out.iterations, out.theta);
  out.converged = end == StageEnd::Converged;
  if (end == StageEnd::Failed) {
    out.message = "Newton's method found no minimum (the criterion could not be evaluated, or decreases without "
                  "bound as the parameters grow)";
  } else if (end == StageEnd::Budget) {
    out.message = "stopped after `max_iterations` = " + std::to_string(max_iterations) + " Newton steps";
  }
  Evaluation ev;
  out.f = evaluate(data, model, out.theta, 0, ev) ? ev.f : std::numeric_limits<double>::quiet_NaN();
  return out;
}

PhysicalCertificate kkt_certificate(const PhysicalData& data, const PhysicalModel& model, const ParamVector& theta) {
  PhysicalCertificate c;
  const int p = model.parameters;
  Evaluation ev;
  if (!evaluate(data, model, theta, 1, ev)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan};
  }
  Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
  for (int a = 0; a < kPayloadParameters; ++a) Z += ev.g(a) * basis(a);
  const Eigen::Matrix4d P = scaled_pseudo_inertia(theta);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(P);
  const Eigen::Vector4d d = eig.eigenvalues();
  const double size = theta.norm();
  const double largest = std::max(d.maxCoeff(), 0.0);
  // The face: eigenvectors of P with eigenvalues at the boundary span U0; the lineality space of
  // the cone at P is everything but U0 Z U0^T.
  Eigen::Matrix4d U0U0 = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) {
    if (d(i) <= kActiveFraction * largest) U0U0 += eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose();
  }
  double stationarity2 = (Z - U0U0 * Z * U0U0).squaredNorm();
  double dual_min = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(Z, Eigen::EigenvaluesOnly).eigenvalues()(0);
  double primal_min = d(0);
  double complementarity = P.cwiseProduct(Z).sum();
  for (int a = kPayloadParameters; a < p; ++a) {
    const double s = theta(a), lambda = ev.g(a);
    if (s > kActiveFraction * largest) stationarity2 += lambda * lambda;
    dual_min = std::min(dual_min, lambda);
    primal_min = std::min(primal_min, s);
    complementarity += s * lambda;
  }
  c.stationarity = size * std::sqrt(stationarity2);
  c.dual_min_eig = size * dual_min;
  c.primal_min_eig = primal_min / data.theta_scale;
  c.complementarity = complementarity;
  return c;
}

}  // namespace spdfit::hexapod::detail
