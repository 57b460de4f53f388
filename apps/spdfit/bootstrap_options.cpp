#include "bootstrap_options.hpp"

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "validators.hpp"

namespace spdfit::cli {

void add_bootstrap_options(CLI::App& sub, BootstrapCli& cli, const std::string& what,
                           const std::string& threads_help) {
  sub.add_option("--bootstrap", cli.replicates, "Resample the rows N times for " + what)
      ->check(CLI::Range(0, 10000000));
  sub.add_option("--confidence", cli.confidence, "The bootstrap intervals' level, a fraction (default 0.95)")
      ->check(open_fraction());
  sub.add_option("--seed", cli.seed, "The bootstrap's seed (default 1); the numbers depend on nothing else");
  sub.add_option("--threads", cli.threads, threads_help)->check(CLI::Range(0u, 1024u));
}

void apply_bootstrap_options(const BootstrapCli& cli, FitOptions& options, const char* threads_also,
                             bool threads_also_given) {
  if (cli.replicates == 0) {
    if (cli.confidence || cli.seed) {
      throw UsageError(std::string(cli.confidence ? "--confidence" : "--seed") +
                       " applies to the bootstrap: give --bootstrap N as well");
    }
    if (cli.threads && !threads_also_given) {
      throw UsageError(threads_also ? "--threads applies to " + std::string(threads_also) +
                                          " and --bootstrap: give one of them, or leave --threads out"
                                    : std::string("--threads applies to the bootstrap: give --bootstrap N as well"));
    }
  }
  options.bootstrap = cli.replicates;
  options.confidence = cli.confidence.value_or(options.confidence);
  options.seed = cli.seed.value_or(options.seed);
  options.threads = cli.threads.value_or(options.threads);
}

}  // namespace spdfit::cli
