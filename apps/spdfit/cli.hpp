// Shared pieces of the command-line tool: the error kinds that decide the exit status, and the
// registration functions of the subcommands.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include "spdfit/io.hpp"
#include "spdfit/outcome.hpp"

namespace CLI {
class App;
}

namespace spdfit::cli {

/// Exit statuses (the CLI contract): 0 success, 1 bad data or numerical failure, 2 usage error.
inline constexpr int kExitSuccess = 0;
inline constexpr int kExitDataError = 1;
inline constexpr int kExitUsageError = 2;

/// A usage error found after parsing (e.g. an option value out of range): exit status 2.
struct UsageError : std::runtime_error, Coded {
  explicit UsageError(const std::string& message, Code code = Code::Argument)
      : std::runtime_error(message), Coded(code, {}) {}
};

/// A numerical failure (or, with its code, bad data) reported by a result: exit status 1. The
/// message is shown as is.
struct DataFailure : std::runtime_error, Coded {
  explicit DataFailure(const std::string& message, Code code = Code::NumericalFailure)
      : std::runtime_error(message), Coded(code, {}) {}
};

class MpiWorld;

/// Options every command shares.
struct GlobalOptions {
  /// The processes spdfit runs among under mpirun (one, without MPI, otherwise).
  MpiWorld* mpi = nullptr;
  bool quiet = false;    ///< suppress warnings on stderr
  bool verbose = false;  ///< say more on stderr (which BLAS kernels run); excludes quiet
  /// How every data file is read: --index-col / --no-index-col set read.index_column.
  io::ReadOptions read;
};

/// A subcommand and its action, run after the whole command line has parsed.
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> run;
};

/// Each adds its subcommand to `app`.
Command add_fit_command(CLI::App& app, const GlobalOptions& global);
Command add_nearest_command(CLI::App& app, const GlobalOptions& global);
Command add_compare_command(CLI::App& app, const GlobalOptions& global);
Command add_solve_command(CLI::App& app, const GlobalOptions& global);
Command add_linkage_command(CLI::App& app, const GlobalOptions& global);
Command add_hexapod_command(CLI::App& app, const GlobalOptions& global);
Command add_experiment_command(CLI::App& app, const GlobalOptions& global);
Command add_demo_command(CLI::App& app, const GlobalOptions& global);
Command add_inertia_command(CLI::App& app, const GlobalOptions& global);

/// Prints "spdfit: warning: MESSAGE" on stderr unless quiet.
void warn(const GlobalOptions& global, const std::string& message);
/// The same for a library warning (its text, spelled for the command line).
inline void warn(const GlobalOptions& global, const Warning& warning) { warn(global, warning.text); }

}  // namespace spdfit::cli
