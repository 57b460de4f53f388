// Internal: a number of the reduced data computed at its first request and kept for the next.
#pragma once

#include <mutex>
#include <optional>

namespace spdfit::detail {

/// The noise estimate of a reduction (noise_variance, reduce.hpp), which auto, the bootstrap's
/// warning and every result's diagnostics may each ask for: computed by the first request, under
/// a lock (a second thread waits for it instead of computing it again), and returned to the others.
/// A copy starts empty, since the copied reduction may then be changed.
class DataCache {
 public:
  DataCache() = default;
  DataCache(const DataCache&) {}
  DataCache& operator=(const DataCache&) {
    const std::lock_guard<std::mutex> lock(mutex_);
    value_.reset();
    return *this;
  }

  /// The kept value, or compute()'s, kept.
  template <typename Compute>
  std::optional<double> get(Compute compute) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!value_) value_ = compute();
    return *value_;
  }

 private:
  mutable std::mutex mutex_;
  mutable std::optional<std::optional<double>> value_;  // outer: computed; inner: the value or nothing
};

}  // namespace spdfit::detail
