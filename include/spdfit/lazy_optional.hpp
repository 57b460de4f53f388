// Numbers computed when they are first read (Diagnostics::noise_sigma, cond_a_scaled, cond_b_scaled).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

namespace spdfit {

namespace detail {

// What LazyOptional and LazyDouble share: a value of type T, known at once or computed by
// `compute` at the first read of the object or of any copy of it (copies share the state).
template <typename T>
class Lazy {
 public:
  Lazy() = default;
  explicit Lazy(T value) : value_(std::move(value)) {}
  static Lazy deferred(std::function<T()> compute) {
    Lazy out;
    out.state_ = std::make_shared<State>();
    out.state_->compute = std::move(compute);
    return out;
  }
  T get() const {
    if (!state_) return value_;
    State& state = *state_;
    std::call_once(state.once, [&state] {
      state.value = state.compute();
      state.compute = nullptr;  // lets go of what the computation needed
      state.done.store(true, std::memory_order_release);
    });
    return state.value;
  }
  bool pending() const { return state_ && !state_->done.load(std::memory_order_acquire); }

 private:
  struct State {
    std::once_flag once;
    std::function<T()> compute;
    T value{};
    std::atomic<bool> done{false};
  };
  T value_{};                     // when not deferred
  std::shared_ptr<State> state_;  // when deferred
};

}  // namespace detail

/// A std::optional<double> whose value may be computed at its first read instead of when the
/// object is made: a diagnostic that can cost more than the estimate it describes (the noise
/// estimate, Diagnostics::noise_sigma) is then paid for only by whoever reads it. It reads like
/// std::optional<double> (has_value, operator bool, operator*, value, value_or, and a conversion).
///
/// Its value does not depend on when it is read: the computation is the one an immediate
/// computation would run, on data that do not change, so it gives the same number to the last bit.
/// Copies share the computation: it runs at most once for an object and all its copies, under
/// std::call_once, so reading from several threads at once is safe. Until it is read, the object
/// keeps what the computation needs alive (for the diagnostics, the fit's reduced data). A read
/// may throw what the computation throws (std::runtime_error when LAPACK's SVD fails); a later
/// read then tries again.
class LazyOptional {
 public:
  using Compute = std::function<std::optional<double>()>;

  LazyOptional() = default;
  LazyOptional(std::nullopt_t) {}                                          // NOLINT: reads as an optional
  LazyOptional(double value) : lazy_(std::optional<double>(value)) {}      // NOLINT
  LazyOptional(std::optional<double> value) : lazy_(value) {}              // NOLINT

  /// A value computed by `compute` at the first read of this object or of a copy of it.
  static LazyOptional deferred(Compute compute) {
    LazyOptional out;
    out.lazy_ = detail::Lazy<std::optional<double>>::deferred(std::move(compute));
    return out;
  }

  /// The value, computed now if it was deferred and not read before.
  std::optional<double> get() const { return lazy_.get(); }
  bool has_value() const { return get().has_value(); }
  explicit operator bool() const { return has_value(); }
  double operator*() const { return *get(); }
  double value() const { return get().value(); }
  double value_or(double fallback) const { return get().value_or(fallback); }
  operator std::optional<double>() const { return get(); }  // NOLINT: reads as an optional

  /// True while the value waits for its first read: reading it would compute it.
  bool pending() const { return lazy_.pending(); }

 private:
  detail::Lazy<std::optional<double>> lazy_;
};

/// A double computed at its first read, as LazyOptional (Diagnostics::cond_a_scaled and
/// cond_b_scaled): it reads like a double (an implicit conversion, get()), with LazyOptional's
/// guarantees: the same number whenever it is read, one computation for all copies, safe to read
/// from several threads.
class LazyDouble {
 public:
  LazyDouble() = default;
  LazyDouble(double value) : lazy_(value) {}  // NOLINT: reads as a double

  /// A value computed by `compute` at the first read of this object or of a copy of it.
  static LazyDouble deferred(std::function<double()> compute) {
    LazyDouble out;
    out.lazy_ = detail::Lazy<double>::deferred(std::move(compute));
    return out;
  }

  /// The value, computed now if it was deferred and not read before.
  double get() const { return lazy_.get(); }
  operator double() const { return get(); }  // NOLINT: reads as a double
  /// True while the value waits for its first read: reading it would compute it.
  bool pending() const { return lazy_.pending(); }

 private:
  detail::Lazy<double> lazy_;
};

}  // namespace spdfit
