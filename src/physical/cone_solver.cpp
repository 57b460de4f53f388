// The barrier path on the cones of physical consistency, Newton's method without constraints, and
// the KKT numbers of a result (cone_solver.hpp).
#include "physical/cone_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace spdfit::physical::detail {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The barrier weight: the first stage's mu is kInitialBarrier f(theta0) / nu (nu the barrier's
// parameter), each later stage's kBarrierDecrease times the previous one's, down to the last
// stage's kFinalBarrier / nu, at which the barrier moves the minimizer by about kFinalBarrier
// relative to f (nu mu bounds the criterion's excess at a barrier centre for a convex criterion):
// below what the data resolve, and near the criterion's rounding level.
constexpr double kInitialBarrier = 1e-2;
constexpr double kBarrierDecrease = 0.05;
constexpr double kFinalBarrier = 1e-14;
// A stage ends when the squared Newton decrement is below kCentering mu (the centring rule of
// barrier methods, for F / mu); the last one when it is below kFinalDecrement or at rounding level.
constexpr double kCentering = 0.1;
// Newton steps of a face solve tried after a barrier stage.
constexpr int kPolishSteps = 12;
// Strictly inside the cone: eigenvalues and scalars above this fraction of the largest eigenvalue
// (the barrier and its Hessian stay finite and resolvable).
constexpr double kInteriorFraction = 1e-13;
// No minimizer: the unconstrained iterates grew beyond this multiple of the start's size.
constexpr double kUnboundedRatio = 1e8;
// An eigenvalue of P_k (or a scalar) below this fraction of the largest counts as on the boundary
// (the barrier leaves active ones at about mu / multiplier, far below it).
constexpr double kActiveFraction = 1e-6;

Eigen::Vector4d eigenvalues(const Eigen::Matrix4d& P) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(P, Eigen::EigenvaluesOnly).eigenvalues();
}

// The scale the nonnegative scalars' floor is relative to: the largest eigenvalue of the bodies,
// or without bodies the largest scalar.
double scalar_scale(const ConeLayout& layout, const Eigen::VectorXd& theta) {
  double scale = 0.0;
  for (int k = 0; k < layout.bodies; ++k) scale = std::max(scale, eigenvalues(body_matrix(theta, k)).maxCoeff());
  if (layout.bodies == 0) {
    for (int j = 0; j < layout.nonnegative; ++j) scale = std::max(scale, theta(layout.nonnegative_begin() + j));
  }
  return scale;
}

// The log-det barrier -sum log det P_k - sum log s_j and its derivatives; false outside the open cone.
struct Barrier {
  double phi = 0.0;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
};

bool barrier(const ConeLayout& layout, const Eigen::VectorXd& theta, int order, Barrier& out) {
  const int p = static_cast<int>(theta.size());
  out.phi = 0.0;
  if (order >= 1) out.g.setZero(p);
  if (order >= 2) out.H.setZero(p, p);
  for (int k = 0; k < layout.bodies; ++k) {
    const Eigen::LLT<Eigen::Matrix4d> llt(body_matrix(theta, k));
    if (llt.info() != Eigen::Success) return false;
    const Eigen::Vector4d diagonal = llt.matrixLLT().diagonal();
    if (!(diagonal.minCoeff() > 0.0)) return false;
    out.phi -= 2.0 * diagonal.array().log().sum();
    if (order < 1) continue;
    const Eigen::Matrix4d Pinv = llt.solve(Eigen::Matrix4d::Identity());
    const int base = kBodyCoordinates * k;
    for (int a = 0; a < kBodyCoordinates; ++a) out.g(base + a) = -coordinate(Pinv, a);
    if (order < 2) continue;
    for (int a = 0; a < kBodyCoordinates; ++a) {
      const Eigen::Matrix4d B = Pinv * basis_matrix(a) * Pinv;  // the Hessian D -> P^-1 D P^-1 applied to E_a
      for (int b = 0; b < kBodyCoordinates; ++b) out.H(base + b, base + a) = coordinate(B, b);
    }
  }
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) {
    if (!(theta(j) > 0.0)) return false;
    out.phi -= std::log(theta(j));
    if (order >= 1) out.g(j) = -1.0 / theta(j);
    if (order >= 2) out.H(j, j) = 1.0 / (theta(j) * theta(j));
  }
  if (order >= 2) out.H = 0.5 * (out.H + out.H.transpose()).eval();
  return std::isfinite(out.phi);
}

// f + mu phi with gradient and Hessian (phi only when constrained).
struct Merit {
  double value = 0.0, rounding = 0.0;
  Eigen::VectorXd g;
  Eigen::MatrixXd H;
};

bool merit(const Criterion& f, const ConeLayout* layout, const Eigen::VectorXd& theta, double mu, int order,
           Merit& out) {
  Evaluation ev;
  if (!f.evaluate(theta, order, ev) || !std::isfinite(ev.f)) return false;
  out.value = ev.f;
  out.rounding = kRoundingMultiple * kEps * std::abs(ev.f);
  if (order >= 1) out.g = std::move(ev.g);
  if (order >= 2) out.H = std::move(ev.H);
  if (layout == nullptr) return true;
  Barrier b;
  if (!barrier(*layout, theta, order, b)) return false;
  if (mu > 0.0) {
    out.value += mu * b.phi;
    out.rounding += kRoundingMultiple * kEps * std::abs(mu * b.phi);
    if (order >= 1) out.g += mu * b.g;
    if (order >= 2) out.H += mu * b.H;
  }
  return std::isfinite(out.value);
}

enum class StageEnd { Converged, Budget, Failed };

// Newton's method on f + mu phi from theta (feasible when `layout` is given: constrained). Ends
// Converged when the squared decrement is below `tolerance` or at the criterion's rounding level
// (no step can decrease it measurably), Budget after the iteration budget, Failed when the merit
// cannot be evaluated at theta or the iterates run off to infinity.
StageEnd newton(const Criterion& f, const ConeLayout* layout, double mu, double tolerance, int max_iterations,
                int& iterations, Eigen::VectorXd& theta, double* value = nullptr) {
  const Eigen::Index p = theta.size();
  Merit cur, trial;
  const double start_norm = std::max(theta.norm(), std::numeric_limits<double>::min());
  Eigen::LLT<Eigen::MatrixXd> llt(p);
  int at_rounding = 0;  // consecutive steps whose predicted decrease was below the merit's rounding
  for (;;) {
    if (!merit(f, layout, theta, mu, 2, cur)) return StageEnd::Failed;
    if (value) *value = cur.value;
    // Levenberg-Marquardt: the smallest shift in {0, 1e-12, 1e-11, ...} times the Hessian's
    // diagonal scale that makes it positive definite (a descent direction far from a minimum).
    const double scale = std::max(cur.H.diagonal().cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
    double shift = 0.0;
    Eigen::MatrixXd H = cur.H;
    for (;;) {
      llt.compute(H);
      if (llt.info() == Eigen::Success && (llt.matrixLLT().diagonal().array() > 0.0).all()) break;
      shift = shift == 0.0 ? 1e-12 * scale : 10.0 * shift;
      if (!(shift < 1e12 * scale)) return StageEnd::Failed;
      H = cur.H;
      H.diagonal().array() += shift;
    }
    const Eigen::VectorXd step = -llt.solve(cur.g);
    const double decrement = -cur.g.dot(step);
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
      const Eigen::VectorXd next = theta + alpha * step;
      if (layout && !strictly_feasible(*layout, next)) continue;
      // The full step at the criterion's trial order (usually taken); a shorter one by its value.
      if (!merit(f, layout, next, mu, alpha == 1.0 ? f.trial_order() : 0, trial)) continue;
      const bool decreases = trial.value <= cur.value - kArmijo * alpha * decrement;
      // Below the merit's resolution the decrease cannot be seen: take the step unless the merit
      // rose beyond its rounding, and let the next gradient judge it.
      const bool rounding_level = alpha * decrement <= cur.rounding && trial.value <= cur.value + cur.rounding;
      if (decreases || rounding_level) {
        theta = next;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No step decreases the merit measurably: the decrement is at the rounding level.
      return decrement <= 1e3 * cur.rounding ? StageEnd::Converged : StageEnd::Failed;
    }
    if (!layout && theta.norm() > kUnboundedRatio * start_norm) return StageEnd::Failed;
  }
}

}  // namespace

bool strictly_feasible(const ConeLayout& layout, const Eigen::VectorXd& theta) {
  if (!theta.allFinite()) return false;
  // A Cholesky factorization succeeds on a semidefinite P with rounding-level pivots; the barrier
  // needs P clearly inside.
  double largest = 0.0;
  for (int k = 0; k < layout.bodies; ++k) {
    const Eigen::Vector4d d = eigenvalues(body_matrix(theta, k));
    if (!(d.minCoeff() > kInteriorFraction * d.maxCoeff()) || !std::isfinite(d.maxCoeff())) return false;
    largest = std::max(largest, d.maxCoeff());
  }
  const double floor = kInteriorFraction * (layout.bodies > 0 ? largest : scalar_scale(layout, theta));
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) {
    if (!(theta(j) > floor) || !(theta(j) > 0.0)) return false;
  }
  return true;
}

Eigen::VectorXd pushed_inside(const ConeLayout& layout, const Eigen::VectorXd& theta, double fraction) {
  Eigen::VectorXd out = theta;
  double largest = 0.0;
  for (int k = 0; k < layout.bodies; ++k) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(body_matrix(theta, k));
    const Eigen::Vector4d d = solver.eigenvalues();
    const double floor = fraction * std::max(d.maxCoeff(), std::numeric_limits<double>::min());
    largest = std::max(largest, d.maxCoeff());
    set_body_matrix(solver.eigenvectors() * d.cwiseMax(floor).asDiagonal() * solver.eigenvectors().transpose(), out,
                    k);
  }
  double scale = layout.bodies > 0 ? largest : scalar_scale(layout, theta);
  if (!(scale > 0.0)) scale = 1.0;  // every scalar <= 0 and no body: a unit start
  const double floor = fraction * scale;
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) out(j) = std::max(out(j), floor);
  return out;
}

double primal_min(const ConeLayout& layout, const Eigen::VectorXd& theta) {
  double out = std::numeric_limits<double>::infinity();
  for (int k = 0; k < layout.bodies; ++k) out = std::min(out, eigenvalues(body_matrix(theta, k)).minCoeff());
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) out = std::min(out, theta(j));
  return out;
}

SolveResult solve_constrained(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& theta0,
                              int max_iterations) {
  SolveResult out;
  out.theta = theta0;
  const double nu = std::max(layout.barrier_parameter(), 1.0);
  Evaluation ev;
  if (!strictly_feasible(layout, theta0) || !f.evaluate(theta0, 0, ev)) {
    out.message = "the start is not strictly inside the cone of physical parameters";
    return out;
  }
  const double mu_final = kFinalBarrier / nu;
  double mu = std::max(kInitialBarrier * std::abs(ev.f) / nu, mu_final);
  std::set<std::vector<int>> tried;  // the faces tried, by their ranks and free scalars
  for (;;) {
    const bool last = mu <= mu_final;
    const StageEnd end = newton(f, &layout, mu, last ? kFinalDecrement : kCentering * mu, max_iterations,
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
    // The face the iterate points to, solved once: quadratic convergence to a minimizer on the
    // boundary, where the path would need many more stages (and, on the interior face, to an
    // interior minimizer).
    std::vector<int> face;
    double largest = 0.0;
    for (int k = 0; k < layout.bodies; ++k) {
      const Eigen::Vector4d d = eigenvalues(body_matrix(out.theta, k));
      face.push_back(static_cast<int>((d.array() > kActiveGuess * d.maxCoeff()).count()));
      largest = std::max(largest, d.maxCoeff());
    }
    const double scale = layout.bodies > 0 ? largest : scalar_scale(layout, out.theta);
    for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j)
      face.push_back(out.theta(j) > kActiveGuess * scale ? 1 : 0);
    if (tried.insert(face).second) {
      int steps = 0;
      const std::optional<SolveResult> solved =
          solve_on_face(f, layout, out.theta, std::min(kPolishSteps, max_iterations - out.iterations), &steps);
      out.iterations += steps;
      if (solved) {
        out.theta = solved->theta;
        out.converged = true;
        break;
      }
    }
    mu = std::max(mu * kBarrierDecrease, mu_final);
  }
  out.f = f.evaluate(out.theta, 0, ev) ? ev.f : std::numeric_limits<double>::quiet_NaN();
  return out;
}

SolveResult solve_unconstrained(const Criterion& f, const Eigen::VectorXd& theta0, int max_iterations) {
  SolveResult out;
  out.theta = theta0;
  double value = std::numeric_limits<double>::quiet_NaN();
  const StageEnd end =
      newton(f, nullptr, 0.0, kFinalDecrement, max_iterations, out.iterations, out.theta, &value);
  out.converged = end == StageEnd::Converged;
  if (end == StageEnd::Failed) {
    out.message = "Newton's method found no minimum (the criterion could not be evaluated, or decreases without "
                  "bound as the parameters grow)";
  } else if (end == StageEnd::Budget) {
    out.message = "stopped after `max_iterations` = " + std::to_string(max_iterations) + " Newton steps";
  }
  // The merit without a barrier is f: its value at the last iterate when Newton's method ended
  // there after evaluating it.
  Evaluation ev;
  out.f = end != StageEnd::Failed && std::isfinite(value) ? value
          : f.evaluate(out.theta, 0, ev)                  ? ev.f
                                                          : std::numeric_limits<double>::quiet_NaN();
  return out;
}

ConeCertificate kkt_certificate(const Criterion& f, const ConeLayout& layout, const Eigen::VectorXd& theta) {
  ConeCertificate c;
  Evaluation ev;
  if (!f.evaluate(theta, 1, ev)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan};
  }
  const double size = theta.norm();
  double stationarity2 = 0.0, dual_min = std::numeric_limits<double>::infinity();
  double primal = std::numeric_limits<double>::infinity(), complementarity = 0.0, largest = 0.0;
  for (int k = 0; k < layout.bodies; ++k) {
    Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
    for (int a = 0; a < kBodyCoordinates; ++a) Z += ev.g(kBodyCoordinates * k + a) * basis_matrix(a);
    const Eigen::Matrix4d P = body_matrix(theta, k);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(P);
    const Eigen::Vector4d d = eig.eigenvalues();
    const double top = std::max(d.maxCoeff(), 0.0);
    largest = std::max(largest, top);
    // The face: eigenvectors of P with eigenvalues at the boundary span U0; the lineality space of
    // the cone at P is everything but U0 Z U0^T.
    Eigen::Matrix4d U0U0 = Eigen::Matrix4d::Zero();
    for (int i = 0; i < 4; ++i) {
      if (d(i) <= kActiveFraction * top) U0U0 += eig.eigenvectors().col(i) * eig.eigenvectors().col(i).transpose();
    }
    stationarity2 += (Z - U0U0 * Z * U0U0).squaredNorm();
    dual_min = std::min(dual_min, eigenvalues(Z)(0));
    primal = std::min(primal, d(0));
    complementarity += P.cwiseProduct(Z).sum();
  }
  const double scale = layout.bodies > 0 ? largest : scalar_scale(layout, theta);
  for (int j = layout.nonnegative_begin(); j < layout.free_begin(); ++j) {
    const double s = theta(j), lambda = ev.g(j);
    if (s > kActiveFraction * scale) stationarity2 += lambda * lambda;
    dual_min = std::min(dual_min, lambda);
    primal = std::min(primal, s);
    complementarity += s * lambda;
  }
  for (int j = layout.free_begin(); j < layout.size(); ++j) stationarity2 += ev.g(j) * ev.g(j);
  c.stationarity = size * std::sqrt(stationarity2);
  c.dual_min_eig = std::isfinite(dual_min) ? size * dual_min : 0.0;
  c.primal_min_eig = std::isfinite(primal) ? primal : 0.0;
  c.complementarity = complementarity;
  return c;
}

}  // namespace spdfit::physical::detail
