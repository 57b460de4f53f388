// Grashof's classification of a four-bar by its link lengths.
#pragma once

#include "spdfit/linkage/freudenstein.hpp"

namespace spdfit::linkage {

/// The motion type of a four-bar with ground a1, input a2, coupler a3, output a4. With s, l the
/// shortest and longest links and p, q the others, the linkage is Grashof (some link turns
/// fully) when s + l < p + q, and then the type depends on which link is the shortest:
/// the input (crank-rocker), the output (rocker-crank), the ground (double-crank, a drag link)
/// or the coupler (double-rocker, the coupler turns fully). s + l == p + q (to a relative
/// 1e-12) is a change-point linkage (it can fold flat: parallelogram, kite); s + l > p + q
/// is non-Grashof, a triple-rocker (no link turns fully).
enum class GrashofType { CrankRocker, RockerCrank, DoubleCrank, DoubleRocker, ChangePoint, TripleRocker };

/// "crank-rocker", "rocker-crank", "double-crank", "double-rocker", "change-point",
/// "triple-rocker".
const char* to_string(GrashofType type);

/// The Grashof type. Preconditions: positive finite lengths (else std::invalid_argument).
GrashofType grashof_type(const FourBar& bar);

}  // namespace spdfit::linkage
