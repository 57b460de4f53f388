// `spdfit demo`: the source documents' experiments on built-in data and what they show. The
// request (trials per part, seed, threads), its option table, the workflow and its report.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "spdfit/options.hpp"

namespace spdfit::experiment {

/// What the demo runs: Monte Carlo trials per part, the seed of every experiment, threads.
struct DemoRequest {
  std::size_t trials = 2000;          ///< per thesis experiment
  std::size_t trials_2x2 = 10000;     ///< per noise level of the 2x2 example
  std::size_t trials_samples = 300;   ///< at each of the larger sample sizes
  std::size_t trials_beyond = 200;    ///< at each point of sections 5 and 7
  std::size_t trials_physical = 100;  ///< at each m of section 6
  std::uint64_t seed = 1;
  unsigned threads = 0;  ///< 0: one per core; the numbers do not depend on it
};

/// The options of `spdfit demo`.
const std::vector<OptionSpec<DemoRequest>>& demo_option_table();

namespace demo {
struct Results;
}

/// What the demo ran, and how long it took.
struct DemoRun {
  DemoRequest request;
  std::shared_ptr<const demo::Results> results;
  double seconds = 0.0;
  unsigned threads = 1;  ///< the threads the trials ran on
};

/// A progress callback for the trials of one part of the demo, named by `label` ("demo: thesis
/// experiment 1"); may return an empty function.
using DemoProgress = std::function<std::function<void(std::size_t, std::size_t)>(const std::string& label)>;

/// The workflow of `spdfit demo`: every experiment of its report, in its order.
DemoRun run_demo(const DemoRequest& request, const DemoProgress& progress = {});

/// The demo's report: the experiments' tables and what they show, wrapped for a terminal.
std::string report(const DemoRun& run);

}  // namespace spdfit::experiment
