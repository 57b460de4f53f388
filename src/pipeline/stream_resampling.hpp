// Internal: streaming for a method known in advance, and the streaming (Poisson) bootstrap's
// factors, read in the one pass of stream_factor.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/method.hpp"
#include "spdfit/stream.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// What the readers of A and B found besides the rows: their warnings (A's, then B's) and their
/// column names.
struct PairInfo {
  std::vector<std::string> warnings;
  std::vector<std::string> a_names, b_names;
};

/// stream_factor for data that `method` (when given) will fit: B with a column count the method
/// does not fit (check_method_fits) is refused at the first block, not after the whole pass.
/// `info`, when given, receives the readers' warnings and column names.
TriangularFactor stream_factor_for(const std::optional<Method>& method, const std::string& a_path,
                                   const std::string& b_path, const StreamOptions& options, PairInfo* info);

/// The factor of all the rows and of each replicate's resample.
struct ResampledFactors {
  TriangularFactor total{1};
  std::vector<TriangularFactor> replicates;
  std::uint64_t groups = 0;  ///< groups of kBootstrapGroupRows rows (the last may be shorter)
  PairInfo info;             ///< the readers' warnings and column names
};

/// Reads A and B as stream_factor does and cuts the rows into consecutive groups of
/// kBootstrapGroupRows (bootstrap.hpp), whatever the block size; each group's factor is merged
/// into `total` and, counted poisson_count(seed, r, group) times, into replicate r's factor, on
/// options.threads threads. Throws as stream_factor_for does.
ResampledFactors stream_resampled_factors(Method method, const std::string& a_path, const std::string& b_path,
                                          const StreamOptions& options, int replicates, std::uint64_t seed);

}  // namespace spdfit::detail
