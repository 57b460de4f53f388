#include "numerics/requested_rank_tolerance.hpp"
#include "spdfit/linkage/structural_error.hpp"

#include <cmath>
#include <stdexcept>

#include "spdfit/linkage/freudenstein.hpp"
#include "gauss_newton.hpp"
#include "linkage_format.hpp"
#include "linkage_inputs.hpp"

namespace spdfit::linkage {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

std::optional<VectorXd> generated_outputs(const Eigen::Vector3d& k, const Eigen::Ref<const VectorXd>& psi,
                                          const Eigen::Ref<const VectorXd>& near, int branch) {
  VectorXd out(psi.size());
  for (Index i = 0; i < psi.size(); ++i) {
    const std::optional<double> phi = output_angle(k, psi(i), branch);
    if (!phi) return std::nullopt;
    out(i) = near(i) - wrap_angle(near(i) - *phi);
  }
  return out;
}

std::optional<VectorXd> structural_error(const Eigen::Vector3d& k, const Eigen::Ref<const VectorXd>& psi,
                                         const Eigen::Ref<const VectorXd>& phi, int branch) {
  const auto generated = generated_outputs(k, psi, phi, branch);
  if (!generated) return std::nullopt;
  return VectorXd(phi - *generated);  // s = phi_pres - phi_gen (notes 3.6), within [-pi, pi]
}

std::optional<int> nearest_branch(const Eigen::Vector3d& k, const Eigen::Ref<const VectorXd>& psi,
                                  const Eigen::Ref<const VectorXd>& phi, const Eigen::Ref<const VectorXd>& weights) {
  const VectorXd root_w = detail::root_weights(weights, psi.size());
  const auto plus = structural_error(k, psi, phi, 1);
  const auto minus = structural_error(k, psi, phi, -1);
  if (!plus || !minus) return std::nullopt;
  return root_w.cwiseProduct(*minus).squaredNorm() < root_w.cwiseProduct(*plus).squaredNorm() ? -1 : 1;
}

StructuralRefinement refine_structural_error(const Eigen::Vector3d& k0, const Eigen::Ref<const VectorXd>& psi,
                                             const Eigen::Ref<const VectorXd>& phi,
                                             const Eigen::Ref<const VectorXd>& weights, int branch,
                                             const GaussNewtonOptions& options) {
  detail::check_positions(psi, phi, weights, 3, "refine_structural_error");
  if (branch != 1 && branch != -1) throw std::invalid_argument("refine_structural_error: branch must be +1 or -1");
  const VectorXd root_w = detail::root_weights(weights, psi.size());
  const VectorXd psi_v = psi, phi_v = phi;

  // r = W^(1/2) s and J = ds/dk = W^(1/2) D^-1 S at the generated angles (eq. 3.16), so that each
  // Gauss-Newton step solves W^(1/2) D^-1 S Delta k = -W^(1/2) s (eq. 3.18).
  const detail::ResidualModel model = [&](const VectorXd& x, VectorXd& r, MatrixXd* J) {
    const Eigen::Vector3d k = x;
    if (!k.allFinite() || !link_lengths(k)) return false;
    const auto generated = generated_outputs(k, psi_v, phi_v, branch);
    if (!generated) return false;
    r = root_w.cwiseProduct(phi_v - *generated);
    if (J) {
      *J = synthesis_matrix(psi_v, *generated);
      for (Index i = 0; i < psi_v.size(); ++i) {
        J->row(i) *= root_w(i) / freudenstein_dphi(k, psi_v(i), (*generated)(i));
      }
    }
    return true;
  };

  StructuralRefinement out;
  out.k = k0;
  VectorXd r0;
  if (!model(k0, r0, nullptr)) {
    out.status = link_lengths(k0) ? SynthesisStatus::NotAssemblable : SynthesisStatus::NoRealLinkage;
    out.message = "the starting linkage k = [" + detail::format(k0(0)) + ", " + detail::format(k0(1)) + ", " +
                  detail::format(k0(2)) + "] " +
                  (out.status == SynthesisStatus::NotAssemblable
                       ? "cannot be assembled at every prescribed input angle"
                       : "is not a real linkage") +
                  ": there is no structural error to minimize";
    return out;
  }
  detail::GaussNewtonSettings settings;
  settings.tolerance = options.tolerance;
  settings.max_iterations = options.max_iterations;
  settings.threshold = spdfit::detail::requested_rank_tolerance(options);
  const detail::GaussNewtonOutcome gn = detail::gauss_newton(model, k0, settings);
  out.k = gn.x;
  out.iterations = gn.iterations;
  out.step_norm = gn.step_norm;
  out.rounding_limited = gn.rounding_limited;
  if (!gn.converged) {
    out.status = SynthesisStatus::Diverged;
    out.message = "structural-error refinement failed: " + gn.message;
  }
  return out;
}

}  // namespace spdfit::linkage
