// Internal: the rank tolerance an options struct asks for, from rank_tolerance or, while it
// exists, the deprecated field `threshold` it replaced (negative: the default rule).
#pragma once

namespace spdfit::detail {

/// options.rank_tolerance when set, else options.threshold (negative: the default rule, which
/// rank_cutoff applies).
template <typename Options>
double requested_rank_tolerance(const Options& options) {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  return options.rank_tolerance ? *options.rank_tolerance : options.threshold;
#pragma GCC diagnostic pop
}

}  // namespace spdfit::detail
