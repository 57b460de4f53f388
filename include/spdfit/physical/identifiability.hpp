// What data determine of a model linear in its parameters, and the evidence of a physically
// consistent fit: shared by `spdfit physical regress` (physical/regress.hpp) and `spdfit payload
// identify` (payload/identify.hpp).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace spdfit::physical {

/// A combination of parameters that the data do not determine: adding any multiple of
/// `coefficients` (over `parameters`, by name) to the estimate leaves every prediction unchanged.
struct UndeterminedCombination {
  std::vector<std::string> parameters;  ///< the parameters it changes, by name
  Eigen::VectorXd coefficients;         ///< their coefficients (unit norm over the data's scaled units)
  std::string text;                     ///< "m c_x + 9.81 b_tau_y (the first moment and the torque bias)"
};

/// The identifiability of the parameters from a regressor: its numerical rank by a rank-revealing
/// (column-pivoted) QR of the regressor with unit-norm columns, the base parameters (the
/// combinations the data determine: the pivoted columns' parameters plus their regression on the
/// others, Gautier's base parameters), the condition number of the column-scaled regressor, and
/// the combinations it leaves undetermined (a basis of its null space, named).
struct Identifiability {
  Eigen::Index parameters = 0;
  Eigen::Index rank = 0;
  /// sigma_max / sigma_min of the regressor with unit-norm columns (inf when rank-deficient).
  double condition = 0.0;
  /// rank x parameters: row i is base parameter i as a combination of the standard parameters
  /// (1 on its own pivot column).
  Eigen::MatrixXd base;
  std::vector<std::string> base_names;  ///< each row of `base` in words ("m_1 + 0.25 I_xx_2")
  std::vector<UndeterminedCombination> undetermined;
  /// Per parameter: true when the data determine it alone (no undetermined combination reaches it).
  std::vector<bool> determined;
};

/// The KKT numbers of a physically consistent fit, for min f over every body's pseudo-inertia
/// P_k >= 0 (and the scalars the model requires to be >= 0), each made dimensionless by the
/// criterion's own scale and the size of the estimate: stationarity (the gradient along the face
/// of the cone the estimate lies on; 0 at a KKT point), primal_min_eig (the smallest eigenvalue of
/// the P_k in kg; >= 0 is physical consistency), dual_min_eig (the smallest eigenvalue of the
/// multipliers Z_k = df/dP_k; >= 0 at a KKT point), complementarity sum <P_k, Z_k> (0 at a KKT
/// point). For a convex criterion (least squares) |complementarity| is the duality gap: the
/// criterion's excess over its global minimum, relative to its scale.
struct Certificate {
  double stationarity = 0.0;
  double primal_min_eig = 0.0;
  double dual_min_eig = 0.0;
  double complementarity = 0.0;
  double duality_gap = 0.0;  ///< |complementarity| for a convex criterion; NaN otherwise
};

}  // namespace spdfit::physical
