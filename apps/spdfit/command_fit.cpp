// spdfit fit --method METHOD [--json | --report] [--output FILE] [--bootstrap N [--confidence F] [--seed S]]
//            [--stream [--block-rows N]] [--threads N] A B
#include <CLI/CLI.hpp>
#include <sys/stat.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>

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

// The options that are the command line's own (what to print, where); the request's come from
// the library's table (fit_option_table).
struct FitOptionsCli {
  std::string method;
  std::string a_path, b_path, output;
  bool json = false;
  bool report = false;
  bool header = false;
  std::string var_a, var_b;
  std::unique_ptr<TableOptions<FitRequest>> table;
};

// The size of a file, 0 when it is not a regular file (standard input, a FILE:NAME array).
std::uint64_t file_bytes(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) ? static_cast<std::uint64_t>(info.st_size) : 0;
}

// "A.mat:accel" for --var-a accel: the library's one way of naming an array in a file. A file
// named with its array already, standard input, or a file without named arrays (text, .npy) takes
// no --var-a (a usage error quoting the option as typed); a file that does not exist is left to
// the reader, which says so.
std::string with_variable(const std::string& path, const std::string& variable, const char* option) {
  if (variable.empty()) return path;
  const std::string typed = std::string(option) + " " + variable;
  if (path == "-") throw UsageError(typed + " names an array in a file, but the file is standard input (-)");
  if (file_bytes(path) > 0 && !io::holds_named_arrays(path)) {
    struct stat info {};
    const bool names_a_file = ::stat(variable.c_str(), &info) == 0;
    throw UsageError(typed + ": " + option + " names a variable inside a .mat or .npz file, but " + path +
                     " is neither (it holds one matrix, no named arrays): drop " + typed +
                     (names_a_file ? "; to read " + variable + " as the data file, give it in " + path + "'s place"
                                   : ""));
  }
  if (!io::split_spec(path).variable.empty()) {
    throw UsageError(typed + " names the array, but " + path +
                     " names one already: give one of them");
  }
  return path + ":" + variable;
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

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (Method m : kSelectableMethods) names.emplace_back(to_string(m));
  return names;
}

}  // namespace

Command add_fit_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<FitOptionsCli>();
  CLI::App* sub = app.add_subcommand("fit", "Estimate X in A X ~= B with one method; print X as CSV");
  sub->add_option("-m,--method", options->method,
                  "ls (least squares), procrustes (symmetric least squares), tls (total least squares), "
                  "tls-sym, tls-psd, spde (area criterion, always SPD), spd-tls (total least squares over "
                  "the SPD matrices), psd-ls (least squares over X >= min-eig I, with a certificate), auto "
                  "(spde, spd-tls or psd-ls, chosen from the data)")
      ->required()
      ->check(CLI::IsMember(method_names()));
  CLI::Option* json =
      sub->add_flag("--json", options->json, "Print the estimate, diagnostics, warnings and the bootstrap's numbers as JSON");
  sub->add_flag("--report", options->report,
                "Print X with its bootstrap standard errors (with --bootstrap), its eigenvalues and the noise "
                "estimate as a table for people")
      ->excludes(json);
  sub->add_flag("--header", options->header,
                "Print X as CSV with a header row and row labels: rows named by A's columns, columns by B's "
                "(numbers where a file has no header row); --json has them as row_names and column_names")
      ->excludes(json)
      ->excludes("--report");
  sub->add_option("-o,--output", options->output,
                  "Write to FILE instead of stdout (X.npy: a NumPy file; X.mat: a MATLAB file with the variable X)");
  options->table = std::make_unique<TableOptions<FitRequest>>(*sub, fit_option_table());
  sub->add_option("--var-a", options->var_a, "The variable of A's .mat or .npz file (as A.mat:NAME)");
  sub->add_option("--var-b", options->var_b, "The variable of B's .mat or .npz file (as B.mat:NAME)");
  sub->add_option("A", options->a_path,
                  "File of A (m x n): delimited text, .npy, .mat or .npz (FILE:NAME names an array), - for "
                  "standard input")
      ->required();
  sub->add_option("B", options->b_path,
                  "File of B (m x n; m x d for ls and tls, X n x d): as A. Without it, --a-cols and --b-cols "
                  "choose A's and B's columns in A's file");

  auto run = [options, &global]() {
    const Method method = *parse_method(options->method);
    if (options->json) check_text_output(options->output, "--json");
    if (options->report) check_text_output(options->output, "--report");
    if (options->header) check_text_output(options->output, "--header");
    const TableOptions<FitRequest>& table = *options->table;
    FitRequest request;
    request.method = method;
    request.read = global.read;
    table.apply(request);
    try {
      check_fit_request(request, table.given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    // The noise estimate and the column-scaled condition numbers (singular values of 2n x 2n and
    // n x n matrices) are shown only by --json and --report: printing X alone, spdfit does not
    // spend the time on them.
    request.options.reported_diagnostics = options->json || options->report;
    MpiWorld& world = *global.mpi;
    if (world.size() > 1 && !request.stream) {
      throw UsageError("under mpirun the processes read parts of A and B a block of rows at a time: add --stream");
    }
    // Under mpirun the cores of a node are shared among its processes (unless --threads says).
    if (world.active() && !table.was_given("threads")) request.options.threads = world.threads_per_process();
    if (options->a_path == "-" && options->b_path == "-") {
      throw UsageError("A and B cannot both be standard input (-)");
    }
    data_read(request, options->b_path);  // the usage errors of --a-cols and --b-cols, before any file is read
    const bool one_file = options->b_path.empty();
    if (one_file && !options->var_a.empty() && !options->var_b.empty() && options->var_a != options->var_b) {
      throw UsageError("--var-a " + options->var_a + " and --var-b " + options->var_b +
                       " name two arrays, but --a-cols and --b-cols take A and B from one: give one of them");
    }
    const std::string a_path = with_variable(options->a_path, one_file && options->var_a.empty() ? options->var_b
                                                                                                 : options->var_a,
                                             one_file && options->var_a.empty() ? "--var-b" : "--var-a");
    const std::string b_path = one_file ? std::string() : with_variable(options->b_path, options->var_b, "--var-b");
    std::vector<std::uint64_t> rows_per_process;
    const std::optional<FitResult> outcome = [&]() -> std::optional<FitResult> {
      // Long runs show a progress line on a terminal (the streaming pass, then the replicates),
      // cleared before anything else is printed.
      ProgressLine reading(global, "reading A and B", file_bytes(options->a_path) + file_bytes(options->b_path));
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
    for (const std::string& w : result.warnings) warn(global, w);
    if (!result.ok()) throw DataFailure(result.message);
    if (result.bootstrap && !options->json && !options->report) {
      warn(global, "--bootstrap's standard errors and intervals are shown with --json or --report; this prints X only");
    }
    if (options->json) {
      // Under mpirun, also how the work was divided among the processes.
      emit(world.active() ? with_fields(to_json(result), {{"processes", world.size()},
                                                          {"rows_per_process", rows_per_process}})
                          : to_json(result),
           options->output);
    } else if (options->report) {
      emit(report(result, report_hints()), options->output);
    } else if (options->header) {
      emit(labelled_csv(result), options->output);
    } else {
      emit_matrix(result.X, options->output);
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
