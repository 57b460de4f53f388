// spdfit fit --method METHOD [--json | --report] [--output FILE] [--bootstrap N [--confidence F] [--seed S]]
//            [--stream [--block-rows N]] [--threads N] A B
#include <CLI/CLI.hpp>
#include <sys/stat.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>

#include "bootstrap_options.hpp"
#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "mpi_world.hpp"
#include "progress_line.hpp"
#include "validators.hpp"
#include "io/containers.hpp"
#include "spdfit/distributed.hpp"
#include "spdfit/fit_files.hpp"

namespace spdfit::cli {

namespace {

struct FitOptionsCli {
  std::string method;
  std::string a_path, b_path, output;
  bool json = false;
  double rank_tolerance = -1.0;
  std::optional<double> noise_ratio;
  std::optional<int> max_iterations;
  std::optional<double> min_eig;
  bool report = false;
  bool header = false;
  BootstrapCli bootstrap;
  bool stream = false;
  StreamOptions stream_options;
  std::string var_a, var_b;
};

// The size of a file, 0 when it is not a regular file (standard input, a FILE:NAME array).
std::uint64_t file_bytes(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) ? static_cast<std::uint64_t>(info.st_size) : 0;
}

// "A.mat:accel" for --var-a accel: the library's one way of naming an array in a file. A file
// named with its array already, or standard input, takes no --var-a (a usage error).
std::string with_variable(const std::string& path, const std::string& variable, const char* option) {
  if (variable.empty()) return path;
  if (path == "-") throw UsageError(std::string(option) + " names an array in a file, but the file is standard input (-)");
  if (!io::detail::split_spec(path).variable.empty()) {
    throw UsageError(std::string(option) + " " + variable + " names the array, but " + path +
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
  sub->add_option("--rank-tol", options->rank_tolerance,
                  "Relative singular-value cut-off for numerical rank (default max(m,n)*eps)")
      ->check(rank_tolerance());
  sub->add_option("--noise-ratio", options->noise_ratio,
                  "sigma_B / sigma_A, the noise in B relative to the noise in A, for the total least-squares "
                  "methods (tls, tls-sym, tls-psd, spd-tls) and auto; default 1")
      ->check(positive());
  sub->add_option("--max-iter", options->max_iterations,
                  "Iteration limit of spd-tls, psd-ls and auto (default 200); then the best iterate, with a "
                  "warning")
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--min-eig", options->min_eig,
                  "psd-ls: the floor epsilon of X >= epsilon I (default 0: positive semidefinite)")
      ->check(non_negative());
  add_bootstrap_options(*sub, options->bootstrap,
                        "standard errors, a percentile interval and the bias of every entry of X (with --json or "
                        "--report)",
                        "Threads for --stream and --bootstrap (default: one per core; the result does not depend on it)");
  CLI::Option* stream =
      sub->add_flag("--stream", options->stream,
                    "Read A and B a block of rows at a time (memory O(threads x block-rows x n + n^2) whatever the "
                    "number of rows; same estimate to rounding)");
  sub->add_option("--block-rows", options->stream_options.block_rows, "Rows per block with --stream")
      ->check(CLI::Range(Eigen::Index{1}, Eigen::Index{1} << 24))
      ->needs(stream);
  sub->add_option("--var-a", options->var_a, "The variable of A's .mat or .npz file (as A.mat:NAME)");
  sub->add_option("--var-b", options->var_b, "The variable of B's .mat or .npz file (as B.mat:NAME)");
  sub->add_option("A", options->a_path,
                  "File of A (m x n): delimited text, .npy, .mat or .npz (FILE:NAME names an array), - for "
                  "standard input")
      ->required();
  sub->add_option("B", options->b_path,
                  "File of B (m x n; m x d for ls and tls, X n x d): as A")
      ->required();

  auto run = [options, &global]() {
    const Method method = *parse_method(options->method);
    if (options->json) check_text_output(options->output, "--json");
    if (options->report) check_text_output(options->output, "--report");
    if (options->header) check_text_output(options->output, "--header");
    FitOptions fit_options;
    fit_options.rank_tolerance = options->rank_tolerance;
    // The noise estimate and the column-scaled condition numbers (singular values of 2n x 2n and
    // n x n matrices) are shown only by --json and --report: printing X alone, spdfit does not
    // spend the time on them.
    fit_options.reported_diagnostics = options->json || options->report;
    // Each of these options applies to some methods only: a usage error with the others.
    auto check = [&](bool given, MethodOption option, const char* spelling) {
      if (!given) return;
      if (const auto why = misplaced_option(option, method, spelling)) throw UsageError(*why);
    };
    check(options->noise_ratio.has_value(), MethodOption::NoiseRatio, "--noise-ratio");
    check(options->max_iterations.has_value(), MethodOption::MaxIterations, "--max-iter");
    check(options->min_eig.has_value(), MethodOption::MinEig, "--min-eig");
    fit_options.noise_ratio = options->noise_ratio.value_or(fit_options.noise_ratio);
    fit_options.max_iterations = options->max_iterations.value_or(fit_options.max_iterations);
    fit_options.min_eig = options->min_eig.value_or(fit_options.min_eig);
    apply_bootstrap_options(options->bootstrap, fit_options, "--stream", options->stream);
    MpiWorld& world = *global.mpi;
    if (world.size() > 1 && !options->stream) {
      throw UsageError("under mpirun the processes read parts of A and B a block of rows at a time: add --stream");
    }
    // Under mpirun the cores of a node are shared among its processes (unless --threads says).
    if (world.active() && !options->bootstrap.threads) fit_options.threads = world.threads_per_process();
    std::optional<StreamOptions> stream;
    if (options->stream) {
      stream = options->stream_options;
      stream->threads = fit_options.threads;
    }
    if (options->a_path == "-" && options->b_path == "-") {
      throw UsageError("A and B cannot both be standard input (-)");
    }
    const std::string a_path = with_variable(options->a_path, options->var_a, "--var-a");
    const std::string b_path = with_variable(options->b_path, options->var_b, "--var-b");
    std::vector<std::uint64_t> rows_per_process;
    const std::optional<FitResult> outcome = [&]() -> std::optional<FitResult> {
      // Long runs show a progress line on a terminal (the streaming pass, then the replicates),
      // cleared before anything else is printed.
      ProgressLine reading(global, "reading A and B", file_bytes(options->a_path) + file_bytes(options->b_path));
      ProgressLine refitting(global, "bootstrap replicates");
      if (stream) stream->progress = test_failure_switch(world.rank(), reading.callback());
      fit_options.progress = refitting.callback();
      if (world.active() && stream) {
        DistributedFit fit = fit_files_distributed(a_path, b_path, method, fit_options, *stream, global.read,
                                                   world.channel());
        rows_per_process = std::move(fit.rows_per_process);
        return std::move(fit.result);
      }
      FitResult result = fit_files(a_path, b_path, method, fit_options, stream, global.read);
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
      nlohmann::json out = result_json(result);
      if (world.active()) {  // how the work was divided among the processes
        out["processes"] = world.size();
        out["rows_per_process"] = rows_per_process;
      }
      emit(out.dump(2) + "\n", options->output);
    } else if (options->report) {
      emit(fit_report(result), options->output);
    } else if (options->header) {
      emit(labelled_matrix_csv(result), options->output);
    } else {
      emit_matrix(result.X, options->output);
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
