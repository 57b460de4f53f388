// spdfit: estimate symmetric positive definite matrices from imperfect measurements.
#include <cstdio>
#include <iostream>
#include <memory>
#include <vector>
#include <string>

#include <CLI/CLI.hpp>

#include "blas_restart.hpp"
#include "cli.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "table_options.hpp"
#include "mpi_world.hpp"
#include "spdfit/blas.hpp"
#include "spdfit/io.hpp"
#include "spdfit/version.hpp"

namespace spdfit::cli {

void warn(const GlobalOptions& global, const std::string& message) {
  if (!global.quiet) std::cerr << "spdfit: warning: " << spell_options(message, Frontend::Cli) << '\n';
}

}  // namespace spdfit::cli

int main(int argc, char** argv) {
  using namespace spdfit::cli;
  restart_for_blas_core(argv);  // first: may restart the program with faster BLAS kernels
  // OpenBLAS's threads, started as it loaded, would spin for about 0.1 s: stopped until needed.
  spdfit::idle_blas_threads();
  CLI::App app{
      "spdfit: estimate a symmetric positive definite matrix X from noisy data A X ~= B\n"
      "(least squares, symmetric Procrustes, total least squares and the area-criterion SPDE)"};
  app.name("spdfit");
  app.set_version_flag("--version", std::string("spdfit ") + spdfit::kVersion);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 bad data or numerical failure, 2 usage error.\n"
      "Run 'spdfit COMMAND --help' for a command's options.");

  // Under mpirun: MPI before anything else, and only process 0 prints (every process parses the
  // command line and fails alike; the distributed fit gives each the same outcome).
  std::unique_ptr<MpiWorld> mpi;
  try {
    mpi = std::make_unique<MpiWorld>();
  } catch (const std::exception& e) {
    std::cerr << "spdfit: error: " << e.what() << '\n';
    return kExitUsageError;
  }
  if (mpi->rank() != 0) {
    if (std::freopen("/dev/null", "w", stdout) == nullptr || std::freopen("/dev/null", "w", stderr) == nullptr) {
      return kExitDataError;
    }
  }

  GlobalOptions global;
  global.mpi = mpi.get();
  // The global options (the library's global_option_table), accepted after the command too
  // (`spdfit fit -q ...`): the commands, added below, inherit this and pass an option they do not
  // know on to the top level.
  TableOptions<spdfit::GlobalRequest> global_options(app, spdfit::global_option_table());
  app.fallthrough();

  const std::vector<Command> commands = {
      add_fit_command(app, global),
      add_nearest_command(app, global),
      add_compare_command(app, global),
      add_solve_command(app, global),
      add_linkage_command(app, global),
      add_hexapod_command(app, global),
      add_experiment_command(app, global),
      add_demo_command(app, global),
      add_inertia_command(app, global),
      add_payload_command(app, global),
      add_physical_command(app, global),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    // CLI11 reports an unknown first word only as a missing subcommand: name it.
    // The command's words (`nearest`, `hexapod simulate`), after any global options, name its help.
    int first = 1;
    while (first < argc && argv[first][0] == '-') ++first;
    std::string known;
    const CLI::App* command_app = nullptr;
    for (const Command& command : commands) {
      known += (known.empty() ? "" : ", ") + command.app->get_name();
      if (first < argc && command.app->get_name() == argv[first]) command_app = command.app;
    }
    if (first < argc && command_app == nullptr && first == 1) {
      message = std::string("unknown command '") + argv[first] + "' (commands: " + known + ")";
    }
    // CLI11's "--scale-b: At Most 1 required but received 2": an option given twice.
    const std::string twice = ": At Most 1 required but received ";
    if (const std::size_t at = message.find(twice); at != std::string::npos) {
      message = message.substr(0, at) + " is given " + message.substr(at + twice.size()) +
                " times: give it once (an option's list of values goes in one argument, comma-separated)";
    }
    std::string help = "spdfit --help";
    if (command_app != nullptr) {
      help = std::string("spdfit ") + argv[first];
      for (int k = first + 1; k < argc && argv[k][0] != '-'; ++k) {
        const std::string word = argv[k];
        const auto named = command_app->get_subcommands([&](const CLI::App* s) { return s->get_name() == word; });
        if (named.empty()) break;
        command_app = named.front();
        help += " " + word;
      }
      help += " --help";
    }
    std::cerr << "spdfit: error: " << message << "\nRun '" << help << "' for usage.\n";
    return kExitUsageError;
  }
  {
    spdfit::GlobalRequest request;
    global_options.apply(request);
    global.quiet = request.quiet;
    global.verbose = request.verbose;
    spdfit::apply_global_options(request, global.read);
  }
  report_blas_core(global);

  try {
    for (const Command& command : commands) {
      if (!command.app->parsed()) continue;
      if (mpi->size() > 1 && command.app->get_name() != "fit") {
        throw UsageError("under mpirun with " + std::to_string(mpi->size()) +
                         " processes only 'spdfit fit --stream' runs (its rows are split among the processes); "
                         "run '" + command.app->get_name() + "' without mpirun");
      }
      command.run();
    }
    return kExitSuccess;
  } catch (const std::exception& e) {
    // The exit status and the usage hint come from the error's code (spdfit/outcome.hpp), never
    // from its text.
    const spdfit::Code code = spdfit::code_of(e);
    std::cerr << "spdfit: error: " << spdfit::spell_options(e.what(), spdfit::Frontend::Cli) << '\n';
    const bool command_line_usage = dynamic_cast<const UsageError*>(&e) != nullptr;
    if (command_line_usage || (spdfit::tier(code) == spdfit::Tier::Usage && code != spdfit::Code::ColumnSelection)) {
      // The command typed, down to its nested subcommand ("physical regress"), as for parse errors.
      std::string command;
      for (const Command& c : commands) {
        if (!c.app->parsed()) continue;
        for (const CLI::App* app = c.app; app != nullptr;) {
          command += app->get_name() + " ";
          const std::vector<CLI::App*> chosen = app->get_subcommands();
          app = chosen.empty() ? nullptr : chosen.front();
        }
      }
      std::cerr << "Run 'spdfit " << command << "--help' for usage.\n";
    }
    return spdfit::exit_status(code);
  }
}
