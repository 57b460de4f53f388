#include "spdfit/inertia_repair.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "spdfit/format.hpp"

namespace spdfit {

namespace {

// The rounding of the second moment's computed eigenvalues, relative to the largest: a few eps
// from forming Sigma from I and the 3 x 3 eigensolver, and the shortest round-trip decimals.
constexpr double kRounding = 16.0 * std::numeric_limits<double>::epsilon();
// A principal moment that the repair changes by more than this fraction is worth a look: a typo
// (a misplaced digit, a product of inertia with the wrong sign) rather than rounding.
constexpr double kTypoFraction = 0.1;

// The inertia metric's QP in Sigma_c's eigenbasis: min ||A delta||^2 over delta >= lo, A = 1 1^T - 1
// (the change of the principal moments a change delta of the second moments makes), G = A^T A.
// Strictly convex: the KKT point of one of the 2^3 active sets is the minimizer.
Eigen::Vector3d inertia_metric_change(const Eigen::Vector3d& lo) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Ones() - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d G = A.transpose() * A;
  Eigen::Vector3d best = lo.cwiseMax(0.0);
  double best_violation = std::numeric_limits<double>::infinity();
  for (int active = 0; active < 8; ++active) {
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();
    int free_index[3], nf = 0;
    for (int i = 0; i < 3; ++i) {
      if (active & (1 << i)) {
        delta(i) = lo(i);
      } else {
        free_index[nf++] = i;
      }
    }
    if (nf > 0) {
      // G_FF delta_F = -G_FA lo_A.
      Eigen::MatrixXd GFF(nf, nf);
      Eigen::VectorXd rhs(nf);
      for (int a = 0; a < nf; ++a) {
        rhs(a) = 0.0;
        for (int b = 0; b < nf; ++b) GFF(a, b) = G(free_index[a], free_index[b]);
        for (int i = 0; i < 3; ++i)
          if (active & (1 << i)) rhs(a) -= G(free_index[a], i) * lo(i);
      }
      const Eigen::VectorXd x = GFF.llt().solve(rhs);
      for (int a = 0; a < nf; ++a) delta(free_index[a]) = x(a);
    }
    // Feasibility of the free ones and the sign of the active ones' multipliers (2 G delta).
    const Eigen::Vector3d gradient = 2.0 * G * delta;
    double violation = 0.0;
    const double scale = std::max(lo.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
    for (int i = 0; i < 3; ++i) {
      if (active & (1 << i)) {
        violation = std::max(violation, -gradient(i) / scale);
      } else {
        violation = std::max(violation, (lo(i) - delta(i)) / scale);
      }
    }
    if (violation < best_violation) {
      best_violation = violation;
      best = delta;
    }
  }
  return best.cwiseMax(lo);  // on the bound exactly where rounding left it a hair below
}

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g%%", 100.0 * fraction);
  return buffer;
}

}  // namespace

std::string_view to_string(InertiaMetric metric) {
  return metric == InertiaMetric::SecondMoment ? "second-moment" : "inertia";
}

std::optional<InertiaMetric> parse_inertia_metric(std::string_view name) {
  if (name == "inertia") return InertiaMetric::Inertia;
  if (name == "second-moment") return InertiaMetric::SecondMoment;
  return std::nullopt;
}

bool InertiaRepairOptions::is_valid(std::string* error) const {
  if (!(min_eig_rel >= 0.0 && min_eig_rel < 1.0)) {
    if (error) *error = "`min_eig_rel` must be a number in [0, 1) (a fraction of the largest second moment)";
    return false;
  }
  return true;
}

InertiaRepairResult repair_inertia(const RigidBodyInertia& body, const InertiaRepairOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  if (!is_well_formed(body, &error)) throw std::invalid_argument(error);

  InertiaRepairResult out;
  out.metric = options.metric;
  out.input = body;
  out.repaired = body;
  const Eigen::Matrix3d inertia = 0.5 * (body.inertia + body.inertia.transpose());
  out.principal_moments_before = principal_inertia(inertia).moments;
  if (inertia.cwiseAbs().maxCoeff() == 0.0) {
    out.warnings.push_back(Warning(Code::PhysicalNotice, "the inertia is all zero for a mass of " + format_number(body.mass) +
                           " kg: a placeholder, not a body's inertia (a point mass at the centre of mass)"));
  }

  // Sigma_c = V diag(sigma) V^T.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(second_moment(inertia));
  if (solver.info() != Eigen::Success) throw std::runtime_error("the 3x3 eigensolver did not converge");
  const Eigen::Vector3d sigma = solver.eigenvalues();
  out.second_moments_before = sigma;
  out.floor = options.min_eig_rel * sigma.cwiseAbs().maxCoeff();
  // Eigenvalues at the floor to rounding (a repaired inertia read back) count as meeting it, so
  // that a repair is idempotent.
  out.changed = sigma.minCoeff() < out.floor - kRounding * sigma.cwiseAbs().maxCoeff();
  if (out.changed) {
    // The change of the second moments in V's basis: the clip raises those below the floor; the
    // inertia metric's QP may also lower the others.
    const Eigen::Vector3d lo = (out.floor - sigma.array()).matrix();
    const Eigen::Vector3d delta = options.metric == InertiaMetric::SecondMoment ? Eigen::Vector3d(lo.cwiseMax(0.0))
                                                                                 : inertia_metric_change(lo);
    // Applied as the change of I it makes (I is linear in Sigma), so that the directions the repair
    // leaves alone keep their digits.
    const Eigen::Matrix3d& V = solver.eigenvectors();
    const Eigen::Matrix3d change = V * delta.asDiagonal() * V.transpose();
    const Eigen::Matrix3d I = inertia + inertia_from_second_moment(0.5 * (change + change.transpose()));
    out.repaired.inertia = 0.5 * (I + I.transpose());
    out.distance = (out.repaired.inertia - body.inertia).norm();
  }
  out.principal_moments = principal_inertia(out.repaired.inertia).moments;
  if (out.changed) {
    double worst = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double before = out.principal_moments_before(i);
      const double moved = std::abs(out.principal_moments(i) - before);
      const double fraction = before != 0.0 ? moved / std::abs(before) : (moved > 0.0 ? 1.0 : 0.0);
      worst = std::max(worst, fraction);
    }
    if (worst > kTypoFraction) {
      out.warnings.push_back(Warning(Code::PhysicalNotice, "the repair changes a principal moment by " + percent(worst) +
                             ": the input may hold a typo (a misplaced digit, a product of inertia with the wrong "
                             "sign) rather than rounding; check it against its source"));
    }
  }

  // The certificate, from the returned inertia.
  const Eigen::Matrix3d S = second_moment(out.repaired.inertia);
  const Eigen::Matrix3d dI = out.repaired.inertia - inertia;
  const Eigen::Matrix3d Z = options.metric == InertiaMetric::SecondMoment
                                ? Eigen::Matrix3d(S - second_moment(inertia))
                                : Eigen::Matrix3d(dI.trace() * Eigen::Matrix3d::Identity() - dI);
  Eigen::Matrix3d shifted = S;
  shifted.diagonal().array() -= out.floor;
  out.certificate.primal_min_eig =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(shifted, Eigen::EigenvaluesOnly).eigenvalues()(0);
  out.certificate.dual_min_eig =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(0.5 * (Z + Z.transpose()), Eigen::EigenvaluesOnly)
          .eigenvalues()(0);
  out.certificate.complementarity = shifted.cwiseProduct(Z).sum();
  return out;
}

}  // namespace spdfit
