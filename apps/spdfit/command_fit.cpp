// spdfit fit --method METHOD [--json | --report] [--output FILE] [--bootstrap N [--confidence F] [--seed S]]
//            [--stream [--block-rows N]] [--threads N] A B
#include <CLI/CLI.hpp>
#include <sys/stat.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <tuple>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "mpi_world.hpp"
#include "progress_line.hpp"
#include "table_options.hpp"
#include "spdfit/distributed.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/named_arrays.hpp"
#include "spdfit/render.hpp"

namespace spdfit::cli {

namespace {

// The size of a file, 0 when it is not a regular file (standard input, a FILE:NAME array).
std::uint64_t file_bytes(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) ? static_cast<std::uint64_t>(info.st_size) : 0;
}

// Test switch: SPDFIT_TEST_MPI_DIE=K kills process K (SIGKILL) after its first block under mpirun,
// as a crashed node would end, so that tests see the other processes end too instead of waiting.
ProgressCallback test_failure_switch(int rank, ProgressCallback progress) {
  const char* die = std::getenv("SPDFIT_TEST_MPI_DIE");
  if (die == nullptr || std::to_string(rank) != die) return progress;
  return [progress](double fraction) {
    std::raise(SIGKILL);
    if (progress) progress(fraction);
  };
}

}  // namespace

Command add_fit_command(CLI::App& app, const GlobalOptions& global) {
  auto table = std::make_shared<std::unique_ptr<TableOptions<FitCommand>>>();
  CLI::App* sub = app.add_subcommand("fit", "Estimate X in A X ~= B with one method; print X as CSV");
  *table = std::make_unique<TableOptions<FitCommand>>(*sub, fit_command_table());

  auto run = [table, &global]() {
    FitCommand command;
    command.fit.read = global.read;
    (*table)->apply(command);
    const OutputRequest& output = command.output;
    if (output.json) check_text_output(output.output, "--json");
    if (output.report) check_text_output(output.output, "--report");
    if (output.header) check_text_output(output.output, "--header");
    FitRequest& request = command.fit;
    try {
      check_fit_request(request, (*table)->given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    // The noise estimate and the column-scaled condition numbers (singular values of 2n x 2n and
    // n x n matrices) are shown only by --json and --report: printing X alone, spdfit does not
    // spend the time on them.
    request.options.reported_diagnostics = output.json || output.report;
    MpiWorld& world = *global.mpi;
    if (world.size() > 1 && !request.stream) {
      throw UsageError("under mpirun the processes read parts of A and B a block of rows at a time: add --stream");
    }
    // Under mpirun the cores of a node are shared among its processes (unless --threads says).
    if (world.active() && !(*table)->was_given("threads")) request.options.threads = world.threads_per_process();
    std::string a_path, b_path;
    try {
      std::tie(a_path, b_path) = fit_command_paths(command);
      data_read_options(request, b_path);  // the usage errors of --a-cols and --b-cols, before any file is read
    } catch (const OptionError& e) {
      throw_usage(e);
    } catch (const io::ColumnSelectionError& e) {
      throw_usage(e);
    }
    std::vector<std::uint64_t> rows_per_process;
    const std::optional<FitResult> outcome = [&]() -> std::optional<FitResult> {
      // Long runs show a progress line on a terminal (the streaming pass, then the replicates),
      // cleared before anything else is printed.
      ProgressLine reading(global, "reading A and B", file_bytes(command.a.path) + file_bytes(command.b.path));
      ProgressLine refitting(global, "bootstrap replicates");
      request.options.progress = refitting.callback();
      request.read_progress = test_failure_switch(world.rank(), reading.callback());
      if (world.active() && request.stream) {
        DistributedFit fit = fit_files_distributed(a_path, b_path, request, world.channel());
        rows_per_process = std::move(fit.rows_per_process);
        return std::move(fit.result);
      }
      FitResult result = fit_files(a_path, b_path, request);
      if (world.active()) rows_per_process = {static_cast<std::uint64_t>(result.diagnostics.m)};
      return result;
    }();
    if (!outcome) return;  // a process other than the first under mpirun: process 0 writes
    const FitResult& result = *outcome;
    for (const auto& w : result.warnings) warn(global, w);
    if (!result.ok()) throw DataFailure(result.message);
    if (result.bootstrap && !output.json && !output.report) {
      warn(global, "--bootstrap's standard errors and intervals are shown with --json or --report; this prints X only");
    }
    if (output.json) {
      // Under mpirun, also how the work was divided among the processes.
      emit(world.active() ? with_fields(to_json(result), {{"processes", world.size()},
                                                          {"rows_per_process", rows_per_process}})
                          : to_json(result),
           output.output);
    } else if (output.report) {
      emit(report(result, report_hints()), output.output);
    } else if (output.header) {
      emit(labelled_csv(result), output.output);
    } else {
      emit_matrix(result.X, output.output);
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
