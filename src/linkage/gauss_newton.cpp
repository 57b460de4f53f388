#include "gauss_newton.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "linkage_format.hpp"
#include "small_least_squares.hpp"

namespace spdfit::linkage::detail {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Step halvings before giving up: 2^-30 ~ 1e-9 of the Gauss-Newton step.
constexpr int kMaxHalvings = 30;

// A residual this small is rounding: no step can lower it reliably (a zero-residual solution).
constexpr double kRoundingLevel = 64 * std::numeric_limits<double>::epsilon();

// The tail of the iteration: the step promises to lower the objective by ||J Delta x||^2, less
// than this fraction of it. The step is then tiny compared with the residual, the linear model
// is accurate, and the change in the objective drowns in its rounding (the residuals are small
// differences of angles of order 1), so comparing objectives says nothing: the full step is
// taken as in the notes' iteration, and convergence is judged by the steps alone.
constexpr double kTail = 1e-10;

// The tail is only where the step is small next to the parameters themselves: a nearly
// singular J also predicts little change for a huge step along its null direction (fuzzing found
// ||Delta k|| = 4e137 taken as a "tail" step), which must then lower the objective like any other.
constexpr double kTailStep = 1e-4;

// Parameters that grow this much beyond the start have run off to infinity along a direction in
// which the error keeps falling (for k: link-length ratios of 1e8, no mechanism): divergence.
constexpr double kRunaway = 1e8;

// In the tail, steps that shrink by less than this factor have stopped converging: they are
// rounding amplified by the conditioning of J, and ||Delta x|| will not get below the tolerance.
constexpr double kNoProgress = 0.5;

}  // namespace

GaussNewtonOutcome gauss_newton(const ResidualModel& model, const VectorXd& x0,
                                const GaussNewtonSettings& settings) {
  GaussNewtonOutcome out;
  out.x = x0;
  VectorXd r, trial_r;
  MatrixXd J;
  if (!model(out.x, r, &J)) throw std::invalid_argument("gauss_newton: the start is infeasible");
  double objective = r.squaredNorm();
  double previous_step_norm = std::numeric_limits<double>::infinity();
  for (;;) {
    // Eq. 3.18: J Delta x = -r in the least-squares sense.
    const VectorXd step = small_least_squares(J, -r, settings.threshold).x;
    out.step_norm = step.norm();
    if (!std::isfinite(out.step_norm)) {
      out.message =
          "the Gauss-Newton step is not finite (D^-1 S blew up: a prescribed position is at a dead point)";
      return out;
    }
    if (out.step_norm < settings.tolerance) {
      out.converged = true;
      return out;
    }
    const bool tail =
        (J * step).squaredNorm() <= kTail * objective && out.step_norm <= kTailStep * (1.0 + out.x.norm());
    if (tail && out.step_norm >= kNoProgress * previous_step_norm) {
      out.converged = true;
      out.rounding_limited = true;
      return out;
    }
    if (out.iterations >= settings.max_iterations) {
      out.message = "Gauss-Newton did not converge in " + std::to_string(settings.max_iterations) +
                    " iterations (last ||Delta k|| = " + format(out.step_norm) + ")";
      return out;
    }
    previous_step_norm = out.step_norm;
    bool accepted = false;
    double t = 1.0;
    for (int h = 0; h <= kMaxHalvings; ++h, t *= 0.5) {
      const VectorXd trial = out.x + t * step;
      if (!model(trial, trial_r, nullptr)) continue;
      const double trial_objective = trial_r.squaredNorm();
      if (tail || trial_objective < objective) {
        out.x = trial;
        objective = trial_objective;
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // At a zero-residual solution rounding alone decides whether a tiny step "lowers" the
      // objective: that is convergence, not divergence.
      if (std::sqrt(objective) <= kRoundingLevel * std::sqrt(static_cast<double>(r.size()))) {
        out.converged = true;
        return out;
      }
      out.message = "Gauss-Newton diverged: no step along the Gauss-Newton direction (||Delta k|| = " +
                    format(out.step_norm) + ", halved up to " + std::to_string(kMaxHalvings) +
                    " times) lowers the error while keeping the linkage real and assemblable";
      return out;
    }
    ++out.iterations;
    if (out.x.norm() > kRunaway * (1.0 + x0.norm())) {
      out.message = "Gauss-Newton diverged: the parameters ran off to ||k|| = " + format(out.x.norm()) +
                    " from " + format(x0.norm()) +
                    " at the start (the error keeps falling along a direction "
                    "that leads to no linkage)";
      return out;
    }
    model(out.x, r, &J);
  }
}

}  // namespace spdfit::linkage::detail
