#include "spdfit/inertia_repair.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace spdfit {

namespace {

// The rounding of the second moment's computed eigenvalues, relative to the largest: a few eps
// from forming Sigma from I and the 3 x 3 eigensolver, and the shortest round-trip decimals.
constexpr double kRounding = 16.0 * std::numeric_limits<double>::epsilon();

}  // namespace

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
  out.input = body;
  out.repaired = body;
  const Eigen::Matrix3d inertia = 0.5 * (body.inertia + body.inertia.transpose());
  out.principal_moments_before = principal_inertia(inertia).moments;

  // Sigma_c = V diag(sigma) V^T; the nearest Sigma' >= floor 1 is V diag(max(sigma, floor)) V^T.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(second_moment(inertia));
  if (solver.info() != Eigen::Success) throw std::runtime_error("the 3x3 eigensolver did not converge");
  const Eigen::Vector3d sigma = solver.eigenvalues();
  out.second_moments_before = sigma;
  out.floor = options.min_eig_rel * sigma.cwiseAbs().maxCoeff();
  // Eigenvalues at the floor to rounding (a repaired inertia read back) count as meeting it, so
  // that a repair is idempotent.
  out.changed = sigma.minCoeff() < out.floor - kRounding * sigma.cwiseAbs().maxCoeff();
  if (out.changed) {
    // Sigma' = Sigma + V diag(max(sigma, floor) - sigma) V^T, applied as the change of I it makes
    // (I is linear in Sigma), so that the directions the clip leaves alone keep their digits.
    const Eigen::Matrix3d& V = solver.eigenvectors();
    const Eigen::Vector3d raise = (out.floor - sigma.array()).max(0.0).matrix();
    const Eigen::Matrix3d change = V * raise.asDiagonal() * V.transpose();
    const Eigen::Matrix3d I = inertia + inertia_from_second_moment(0.5 * (change + change.transpose()));
    out.repaired.inertia = 0.5 * (I + I.transpose());
    out.distance = (out.repaired.inertia - body.inertia).norm();
  }
  out.principal_moments = principal_inertia(out.repaired.inertia).moments;

  // The certificate, from the returned inertia.
  const Eigen::Matrix3d S = second_moment(out.repaired.inertia);
  const Eigen::Matrix3d Z = S - second_moment(inertia);
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
