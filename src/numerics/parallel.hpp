// Internal: the one pool of worker threads behind the Monte Carlo experiments and the bootstrap.
#pragma once

#include <cstddef>
#include <functional>

namespace spdfit::detail {

/// Runs fn(i) for every i in [0, count) on up to `threads` threads (0: one per core), handing out
/// indices in order. With `progress`, the calling thread reports progress(done, count) about every
/// 100 ms while the workers run, and once at the end; without it, the calling thread works too.
/// The first exception thrown by fn stops the hand-out and is rethrown here once every thread has
/// stopped.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& fn,
                  const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace spdfit::detail
