// Internal: the geometric pieces of the hexapod model shared by the validity check and the
// public model functions (which check validity first; these do not).
#pragma once

#include "spdfit/hexapod/geometry.hpp"

namespace spdfit::hexapod::detail {

/// r_i = R p_i: the payload joints relative to the centre of mass, in {B} axes.
Points lever_arms(const Geometry& geometry);

/// b_i - q_i: the strut vectors from base joint to payload joint, in {B}.
Points strut_vectors(const Geometry& geometry);

/// J with rows [u_i^T, (r_i x u_i)^T] (model.hpp), for struts of nonzero length.
Matrix6d jacobian_unchecked(const Geometry& geometry);

/// The RMS length of the lever arms r_i (1 when they are all zero): the payload's size, used
/// to make J's angular columns commensurate with its linear ones.
double characteristic_length(const Geometry& geometry);

/// Throws std::invalid_argument with Geometry::is_valid's message when the geometry is invalid.
void require_valid(const Geometry& geometry);

}  // namespace spdfit::hexapod::detail
