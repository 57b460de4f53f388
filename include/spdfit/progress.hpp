// Progress of long computations, for front-ends that show it (the command line's progress line).
#pragma once

#include <functional>

namespace spdfit {

/// Called by a long computation as it goes, with the fraction of the work done, in [0, 1]
/// (non-decreasing; 1 once, at the end). It may be called from any of the computation's threads,
/// but never by two at once. Keep it cheap: it runs in the computation's loop. An empty function
/// (the default) is not called.
using ProgressCallback = std::function<void(double fraction_done)>;

}  // namespace spdfit
