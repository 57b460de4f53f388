// How a linkage synthesis ended.
#pragma once

namespace spdfit::linkage {

/// The outcome of a synthesis step on valid input (misuse throws std::invalid_argument instead).
enum class SynthesisStatus {
  Success,
  NoRealLinkage,   ///< the parameters k give a negative or infinite length, or a3^2 <= 0 (eq. 3.4)
  NotAssemblable,  ///< the linkage cannot be assembled at some prescribed input angle
  Diverged,        ///< Gauss-Newton did not converge (see the message)
};

/// "success", "no real linkage", "not assemblable", "diverged".
const char* to_string(SynthesisStatus status);

}  // namespace spdfit::linkage
