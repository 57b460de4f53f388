// Internal: one physical identification from a triangular factor (physical.cpp), shared by the
// public entry points and the bootstrap's replicates (physical_bootstrap.cpp).
#pragma once

#include <functional>
#include <optional>
#include <Eigen/Core>

#include "hexapod/physical_model.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::hexapod::detail {

/// The estimate from `factor` with the model of `geometry` (options valid, the design of full
/// rank; the caller checks both). `reported` off leaves out what only a report needs (the
/// certificates, the modes, the warnings): the bootstrap's replicates. Throws
/// std::invalid_argument when the data cannot identify a parameter.
PhysicalEstimate fit_physical(const TriangularFactor& factor, const PhysicalModel& model, const Geometry& geometry,
                              const PhysicalOptions& options, bool reported = true);

/// The options of a bootstrap replicate's fit: no bootstrap of its own, no plausibility check.
PhysicalOptions replicate_options(PhysicalOptions options);

/// Fills estimate.bootstrap from options.bootstrap replicates on options.threads threads: replicate
/// r's estimate is `replicate(r)` (empty, not ok, or a std::invalid_argument thrown: a failed
/// replicate).
using PhysicalReplicate = std::function<std::optional<PhysicalEstimate>(std::size_t)>;
void bootstrap_physical(PhysicalEstimate& estimate, const Geometry& geometry, const PhysicalOptions& options,
                        const PhysicalReplicate& replicate);

/// The same, each replicate a multinomial resample of the rows of A and B refitted by fit_physical.
void bootstrap_physical(PhysicalEstimate& estimate, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                        const PhysicalModel& model, const Geometry& geometry, const PhysicalOptions& options);

}  // namespace spdfit::hexapod::detail
