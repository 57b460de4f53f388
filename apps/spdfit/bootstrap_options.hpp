// The bootstrap's options, shared by `fit` and `hexapod identify`: --bootstrap, --confidence,
// --seed and --threads, their checks, and their copy into FitOptions.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "spdfit/fit_options.hpp"

namespace CLI {
class App;
}

namespace spdfit::cli {

/// The bootstrap's options as given on the command line.
struct BootstrapCli {
  int replicates = 0;
  std::optional<double> confidence;
  std::optional<std::uint64_t> seed;
  std::optional<unsigned> threads;
};

/// Adds --bootstrap (described by `what`), --confidence, --seed and --threads (described by
/// `threads_help`) to `sub`.
void add_bootstrap_options(CLI::App& sub, BootstrapCli& cli, const std::string& what, const std::string& threads_help);

/// Copies the options into `options`. A UsageError for --confidence or --seed without
/// --bootstrap, and for --threads without --bootstrap unless `threads_also` (the other option
/// --threads serves, e.g. "--stream") was given: `threads_also_given`.
void apply_bootstrap_options(const BootstrapCli& cli, FitOptions& options, const char* threads_also = nullptr,
                             bool threads_also_given = false);

}  // namespace spdfit::cli
