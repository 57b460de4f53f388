// The barrier path of physical identification: Newton stages on the criterion plus mu times the
// log-det barrier of the pseudo-inertia cone, the face solves tried between them, the unconstrained
// Newton method of the grey-box fit, and the KKT numbers of a result.
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

// The barrier weight: the first stage's mu is kInitialBarrier f(theta0) / nu (nu = 4 + the strut
// masses, the barrier's parameter), each later stage's kBarrierDecrease times the previous one's,
// down to the last stage's kFinalBarrier / nu, at which the barrier moves the minimizer by about
// kFinalBarrier relative to f0 (nu mu bounds the criterion's excess at a barrier centre for a
// convex criterion): below what the data resolve, and near the criterion's rounding level.
constexpr double kInitialBarrier = 1e-2;
constexpr double kBarrierDecrease = 0.05;
constexpr double kFinalBarrier = 1e-14;
// A stage ends when the squared Newton decrement is below kCentering mu (the centring rule of
// barrier methods, for F / mu); the last one when it is below kFinalDecrement or at rounding level.
constexpr double kCentering = 0.1;
// Newton steps of a face solve tried after a barrier stage.
constexpr int kPolishSteps = 12;
// Strictly inside the cone: P's eigenvalues and the strut masses above this fraction of P's largest
// eigenvalue (the barrier and its Hessian stay finite and resolvable).
constexpr double kInteriorFraction = 1e-13;
// No minimizer: the unconstrained iterates grew beyond this multiple of the start's size.
constexpr double kUnboundedRatio = 1e8;
// An eigenvalue of P (or a strut mass) below this fraction of P's largest counts as on the
// boundary (the barrier leaves active ones at about mu / multiplier, far below it).
constexpr double kActiveFraction = 1e-6;

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
    const Eigen::Matrix4d B = Pinv * basis_matrix(a) * Pinv;  // the Hessian D -> P^-1 D P^-1 applied to E_a
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
    const auto rank = static_cast<int>((d.array() > kActiveGuess * d.maxCoeff()).count());
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
  for (int a = 0; a < kPayloadParameters; ++a) Z += ev.g(a) * basis_matrix(a);
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
