// Position analysis of a four-bar driven by its input link: the output angle on both assembly
// branches, the transmission angle, the dead points, and whether a motion stays on one branch.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/grashof.hpp"

namespace spdfit::linkage {

/// The transmission angle mu in [0, pi] at input angle psi (radians): the angle between the
/// coupler and the output link, from the triangle of the coupler, the output link and the
/// diagonal e from the crank tip to the output pivot (e^2 = a1^2 + a2^2 - 2 a1 a2 cos psi):
/// cos mu = (a3^2 + a4^2 - e^2) / (2 a3 a4). The same on both branches. NaN when the linkage
/// cannot be assembled at psi. mu = 0 or pi is a dead point; designers keep mu within about
/// 40..140 degrees so that the coupler can push the output link.
double transmission_angle(const FourBar& bar, double psi);

/// The input angles in (-pi, pi], ascending, at which the linkage driven by its input is at a
/// dead point: the coupler and output link in line (e = a3 + a4 or e = |a3 - a4|, mu = pi or 0).
/// There the input angle reaches a limit and the two assembly branches meet; a crank input
/// (crank-rocker, double-crank) has none. Cost: O(1).
std::vector<double> dead_points(const FourBar& bar);

/// The smallest and largest transmission angle while the input turns from psi_lo to psi_hi
/// (radians, psi_lo <= psi_hi). cos mu is monotonic in cos psi, so the extremes are at the
/// ends and at the multiples of pi in between: exact, not sampled. Where the linkage cannot be
/// assembled the angle counts as 0 or pi (whichever limit it passed).
struct AngleRange {
  double min = 0.0, max = 0.0;
};
AngleRange transmission_angle_range(const FourBar& bar, double psi_lo, double psi_hi);

/// What a designer checks on a synthesized function generator: its Grashof type, the range of
/// the transmission angle over the prescribed motion, and whether the linkage moves through
/// every prescribed position on one assembly branch.
struct MotionCheck {
  GrashofType grashof = GrashofType::TripleRocker;
  AngleRange transmission;           ///< radians, over [min psi_i, max psi_i]
  /// Input angles of dead points inside that range (radians), ascending; the first
  /// kMaxListedDeadPoints when the range spans many turns.
  std::vector<double> dead_points;
  static constexpr std::size_t kMaxListedDeadPoints = 64;
  /// True when the linkage cannot move through all prescribed positions on one branch without
  /// passing a dead point: a dead point lies in the swept input range (the input cannot turn
  /// through it, and past it only the other branch continues), or some prescribed output angle
  /// lies nearer to the other branch than to the one the linkage is assembled on.
  bool branch_defect = false;
  std::string branch_defect_reason;  ///< plain words; empty when there is no defect
};

/// The check of `bar` driven through the prescribed inputs psi (radians, in the order of the
/// motion; the input sweeps from min psi to max psi) on branch `branch` (+1 or -1), with the
/// prescribed outputs phi. Preconditions: equal lengths, at least one position.
MotionCheck check_motion(const FourBar& bar, const Eigen::Ref<const Eigen::VectorXd>& psi,
                         const Eigen::Ref<const Eigen::VectorXd>& phi, int branch);

/// One input angle of an analysis.
struct AnalysisSample {
  double psi = 0.0;
  std::optional<double> phi_plus, phi_minus;   ///< output angle on branch +1 / -1 (output_angle)
  std::optional<double> transmission_angle;    ///< nothing when the linkage cannot be assembled
};

/// The position analysis of a four-bar over input angles psi (radians).
struct Analysis {
  FourBar bar;
  Eigen::Vector3d k = Eigen::Vector3d::Zero();  ///< Freudenstein parameters (eq. 3.4)
  GrashofType grashof = GrashofType::TripleRocker;
  /// The input can turn through 360 degrees: the diagonal e, which ranges over [|a1 - a2|,
  /// a1 + a2], always fits the coupler-output triangle: a1 + a2 <= a3 + a4 and
  /// |a1 - a2| >= |a3 - a4| (a crank-rocker or double-crank, or a change-point linkage whose
  /// input is a shortest link).
  bool input_fully_rotates = false;
  std::vector<double> dead_points;              ///< input angles, (-pi, pi]
  std::vector<AnalysisSample> samples;          ///< one per psi; each branch's phi unwrapped along psi
  /// Over the part of [min psi, max psi] where the linkage can be assembled (exact, as
  /// transmission_angle_range); nothing when it cannot be assembled anywhere in the range.
  std::optional<AngleRange> transmission;
};

/// phi(psi) on both branches where the linkage can be assembled, the transmission angle, and
/// the dead points (notes 002 section 3.3.3 for the equation; analysis is its inverse use).
/// Preconditions: positive finite lengths, finite psi (else std::invalid_argument).
/// Cost: O(len(psi)).
Analysis analyze(const FourBar& bar, const Eigen::Ref<const Eigen::VectorXd>& psi);

}  // namespace spdfit::linkage
