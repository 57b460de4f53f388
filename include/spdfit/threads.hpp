// How many worker threads a "threads" option stands for: shared by the streaming fit, the
// Monte Carlo experiments and anything else that runs on all cores.
#pragma once

namespace spdfit {

/// The number of worker threads `requested` stands for: `requested` itself when positive, else
/// std::thread::hardware_concurrency() (1 when the hardware does not say). Cost O(1).
unsigned resolve_threads(unsigned requested);

}  // namespace spdfit
