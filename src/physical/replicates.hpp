// Internal: the bootstrap's summary of replicate vectors, entry by entry (the physical fits'
// bootstraps: payload identify, physical regress), and the multinomial resample of samples.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace spdfit::physical::detail {

/// Per entry: the replicates' standard deviation (divisor N - 1) and the two-sided percentile
/// interval at `level` (numpy.quantile's linear interpolation between order statistics), over the
/// replicates that have the entry finite; NaN where fewer than 2 do. `replicates` holds one vector
/// per replicate (nothing for a failed one), each of the estimate's size.
struct EntrySummary {
  Eigen::VectorXd standard_errors, lower, upper;
};
EntrySummary summarize(Eigen::Index size, const std::vector<std::optional<Eigen::VectorXd>>& replicates,
                       double level);

/// Replicate r's counts of `samples` samples drawn with replacement by a generator keyed by
/// (seed, r) (the fit's bootstrap's keying: trial_seed).
std::vector<std::uint32_t> resample_counts(Eigen::Index samples, std::uint64_t seed, std::size_t replicate);

}  // namespace spdfit::physical::detail
