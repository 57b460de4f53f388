// Prescribed input-output pairs for a function generator: the steering condition and named
// functions y = f(x) mapped onto input and output angle ranges.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace spdfit::linkage {

/// How the inputs are distributed over their range (notes 002 section 3.3.3: "how should the
/// input data be distributed? ... usually requires some experimentation").
enum class Spacing {
  Uniform,    ///< equal steps, both ends included
  Chebyshev,  ///< Chebyshev nodes lo + (hi - lo)(1 - cos((2j - 1) pi / 2N)) / 2, j = 1..N: denser
              ///< near the ends, the classical choice of precision points
};

/// N points over [lo, hi], ascending. Preconditions: N >= 1, finite lo < hi (else
/// std::invalid_argument); N = 1 gives the midpoint.
Eigen::VectorXd spaced_points(double lo, double hi, int n, Spacing spacing);

/// Input-output angle changes (radians) from the dial zeros: psi = alpha + delta_psi,
/// phi = beta + delta_phi (eq. 3.6).
struct PrescribedPairs {
  Eigen::VectorXd delta_psi, delta_phi;
};

/// The steering condition S = sin(dphi - dpsi) - rho sin(dpsi) sin(dphi) = 0 (eq. 3.1, 3.5),
/// rho = track / wheelbase: the value of S.
double steering_condition(double delta_psi, double delta_phi, double rho);

/// The output change that satisfies the steering condition exactly: cot(dpsi) - cot(dphi) = rho
/// (Ackermann), i.e. dphi = atan2(sin dpsi, cos dpsi - rho sin dpsi), continuous through 0.
double steering_output(double delta_psi, double rho);

/// Pairs for the steering condition at inputs delta_psi spaced over [lo, hi] (radians).
/// Preconditions: finite rho; as spaced_points.
PrescribedPairs steering_pairs(double rho, double lo, double hi, int n, Spacing spacing);

/// Dial zeros (eq. 3.6), radians: the input and output angles at which the prescribed changes
/// delta_psi and delta_phi are zero.
struct DialZeros {
  double alpha = 0.0, beta = 0.0;
};

/// The classic trapezoid (Jeantaud) dial zeros for a steering linkage whose tie rod lies behind
/// the axle and whose arm lines meet at the middle of the rear axle: with the ground line
/// from the input kingpin to the output kingpin (the x axis pointing to the car's left, so that
/// counter-clockwise is a left turn and the output wheel is the inner one, as eq. 3.5 has it),
/// alpha = 90 deg - atan(rho / 2) and beta = 90 deg + atan(rho / 2). The default dial zeros of
/// `spdfit linkage synthesize --steering`.
DialZeros trapezoid_dial_zeros(double rho);

/// The names function_pairs accepts: linear, square, cube, sqrt, reciprocal, exp, ln, log10,
/// sin, cos, tan (x in radians for the last three).
const std::vector<std::string>& function_names();

/// Pairs for y = f(x), x spaced over [x_lo, x_hi] and mapped linearly onto input changes
/// [psi_lo, psi_hi]; y mapped linearly from [f(x_lo), f(x_hi)] onto [phi_lo, phi_hi] (angles in
/// radians). Preconditions: a known name, f defined and finite on the points, f(x_lo) !=
/// f(x_hi), finite ranges (else std::invalid_argument, naming the problem).
PrescribedPairs function_pairs(const std::string& name, double x_lo, double x_hi, double psi_lo, double psi_hi,
                               double phi_lo, double phi_hi, int n, Spacing spacing);

}  // namespace spdfit::linkage
