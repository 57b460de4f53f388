// Internal: the streaming (Poisson) bootstrap's factors, read in the one pass of stream_factor.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "spdfit/stream.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// The factor of all the rows and of each replicate's resample.
struct ResampledFactors {
  TriangularFactor total{1};
  std::vector<TriangularFactor> replicates;
  std::uint64_t groups = 0;  ///< groups of kBootstrapGroupRows rows (the last may be shorter)
};

/// Reads A and B as stream_factor does and cuts the rows into consecutive groups of
/// kBootstrapGroupRows (bootstrap.hpp), whatever the block size; each group's factor is merged
/// into `total` and, counted poisson_count(seed, r, group) times, into replicate r's factor, on
/// options.threads threads. Throws as stream_factor does.
ResampledFactors stream_resampled_factors(const std::string& a_path, const std::string& b_path,
                                          const StreamOptions& options, int replicates, std::uint64_t seed);

}  // namespace spdfit::detail
