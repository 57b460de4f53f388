// The streaming fit split among processes: a counting pass, row ranges, each process's factor,
// and a binary merge tree; the communication is the caller's (Channel: MPI in the command line).
#include "spdfit/distributed.hpp"

#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "factor/basic_reduction.hpp"
#include "io/split_file.hpp"
#include "pipeline/sentinels.hpp"
#include "pipeline/noise_files.hpp"
#include "pipeline/pair_checks.hpp"
#include "spdfit/options.hpp"
#include "pipeline/stream_resampling.hpp"
#include "spdfit/fit_files.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit {

namespace {

using detail::ResampledFactors;
using io::detail::LinePosition;
using io::detail::SplitFile;

// Thrown into a process's reading when another process has failed.
struct StoppedByPartner : std::exception {
  const char* what() const noexcept override { return "stopped: another process failed"; }
};

// Length-prefixed fields, for the messages between processes.
void put(std::string& out, std::string_view field) {
  out += std::to_string(field.size());
  out += ':';
  out += field;
}
void put(std::string& out, std::uint64_t number) { put(out, std::to_string(number)); }

class Fields {
 public:
  explicit Fields(std::string_view text) : rest_(text) {}
  std::string_view next() {
    const std::size_t colon = rest_.find(':');
    if (colon == std::string_view::npos) throw std::runtime_error("distributed fit: a malformed message");
    const std::size_t size = std::stoull(std::string(rest_.substr(0, colon)));
    if (size > rest_.size() - colon - 1) throw std::runtime_error("distributed fit: a malformed message");
    const std::string_view field = rest_.substr(colon + 1, size);
    rest_.remove_prefix(colon + 1 + size);
    return field;
  }
  std::uint64_t number() { return std::stoull(std::string(next())); }
  bool done() const { return rest_.empty(); }

 private:
  std::string_view rest_;
};

// A process's outcome of a step: 'o' and its payload, 'f' and its failure, or 's' (stopped
// because another process failed).
std::string describe_current_exception() {
  std::string out;
  try {
    throw;
  } catch (const StoppedByPartner&) {
    return "s";
  } catch (const io::DataError& e) {
    out = "fD";
    put(out, e.source());
    put(out, e.line());
    put(out, e.column());
    put(out, e.problem());
  } catch (const std::invalid_argument& e) {
    out = "fI";
    put(out, e.what());
  } catch (const std::exception& e) {
    out = "fR";
    put(out, e.what());
  }
  return out;
}

[[noreturn]] void throw_failure(std::string_view failure) {
  Fields fields(failure.substr(2));
  switch (failure[1]) {
    case 'D': {
      const std::string source(fields.next());
      const std::uint64_t line = fields.number();
      const std::uint64_t column = fields.number();
      throw io::DataError(source, line, column, std::string(fields.next()));
    }
    case 'I':
      throw std::invalid_argument(std::string(fields.next()));
    default:
      throw std::runtime_error(std::string(fields.next()));
  }
}

// Runs `work` on this process and gathers every process's payload, in rank order. When any
// process failed, every process throws the failure of the first in rank order (the first in
// the files' order). In a step that announces failures (the long reading), a failing process
// tells the others at once, and they stop at their next block.
std::vector<std::string> step(Channel& channel, const std::function<std::string()>& work, bool announce = false) {
  std::string mine;
  try {
    mine = "o" + work();
  } catch (...) {
    mine = describe_current_exception();
    if (announce && mine[0] == 'f') channel.announce_failure();
  }
  std::vector<std::string> all = channel.all_gather(mine);
  if (announce) {
    std::vector<int> announced;
    for (std::size_t k = 0; k < all.size(); ++k) {
      if (all[k][0] == 'f') announced.push_back(static_cast<int>(k));
    }
    channel.settle(announced);
  }
  for (const std::string& outcome : all) {
    if (outcome[0] == 'f') throw_failure(outcome);
  }
  for (std::string& outcome : all) outcome.erase(0, 1);
  return all;
}

std::string encode(const std::vector<std::uint64_t>& numbers) {
  std::string out;
  for (std::uint64_t x : numbers) put(out, x);
  return out;
}

std::vector<std::uint64_t> decode(std::string_view text) {
  std::vector<std::uint64_t> numbers;
  Fields fields(text);
  while (!fields.done()) numbers.push_back(fields.number());
  return numbers;
}

// The first row of each process, and m at the end: m k / K, rounded up to whole bootstrap groups
// when `group` > 1 (so that process 0 reads rows whenever there are any: it reads the header
// and reports the files' warnings).
std::vector<std::uint64_t> boundaries(std::uint64_t m, int parts, std::uint64_t group) {
  std::vector<std::uint64_t> first(static_cast<std::size_t>(parts) + 1);
  for (int k = 0; k <= parts; ++k) {
    const auto p = static_cast<std::uint64_t>(parts);
    const auto kk = static_cast<std::uint64_t>(k);
    const std::uint64_t share = io::detail::scaled_share(m, kk, p) + (m % p * kk % p != 0 ? 1 : 0);  // rounded up
    first[static_cast<std::size_t>(k)] = std::min(m, (share + group - 1) / group * group);
  }
  return first;
}

// The factors one process holds: of its rows, and with --bootstrap of each replicate's resample.
struct PartFactors {
  ResampledFactors factors;  // total (and replicates, groups with the bootstrap)

  std::string serialize() const {
    std::string out;
    put(out, factors.total.serialize());
    put(out, factors.groups);
    for (const TriangularFactor& r : factors.replicates) put(out, r.serialize());
    return out;
  }
  // Appends the rows of `later`'s factors (the next processes' rows) to these.
  void merge(std::string_view later) {
    Fields fields(later);
    factors.total.merge(TriangularFactor::deserialize(fields.next()));
    factors.groups += fields.number();
    for (TriangularFactor& r : factors.replicates) r.merge(TriangularFactor::deserialize(fields.next()));
  }
};

// Merges every process's factors into process 0's along a binary tree: at step s = 1, 2, 4, ...
// process k (a multiple of 2s) merges in those of process k + s. The order of the rows is kept,
// and for a given number of processes the result is the same run to run.
void merge_tree(Channel& channel, PartFactors& part) {
  const int rank = channel.rank();
  const int size = channel.size();
  for (int s = 1; s < size; s *= 2) {
    if (rank % (2 * s) == s) {
      channel.send(rank - s, part.serialize());
      return;
    }
    if (rank % (2 * s) == 0 && rank + s < size) part.merge(channel.receive(rank + s));
  }
}

}  // namespace

DistributedFit fit_files_distributed(const std::string& a_path, const std::string& b_path, Method method,
                                     const FitOptions& options, const StreamOptions& stream,
                                     const io::ReadOptions& read, Channel& channel) {
  const int rank = channel.rank();
  const int size = channel.size();
  DistributedFit out;
  if (size == 1) {  // one process reads every format, as fit_files does
    out.result = fit_files(a_path, b_path, method, options, stream, read);
    out.rows_per_process = {static_cast<std::uint64_t>(out.result->diagnostics.m)};
    return out;
  }
  std::string error;
  if (!options.is_valid(&error)) throw OptionError(error);
  if (options.robust != RobustLoss::None) {
    throw OptionError("`robust` reweighs every row at each of its iterations, which processes that each read a part "
                      "of the files once cannot: fit the rows in memory in one process (without mpirun)",
                      Code::OptionConflict, "robust");
  }
  if (stream.block_rows < 1) throw std::invalid_argument("block_rows must be at least 1");

  // The counting pass: each process opens both files (learning a text file's layout from its
  // first lines) and counts the lines of its part of their bytes.
  // With an empty b_path, A's and B's columns are in the one file (read.columns): it alone is split.
  const bool one_file = detail::checked_pair_read(b_path, read).columns.size() == 2;
  std::optional<SplitFile> a, b;
  const std::vector<std::string> counts = step(channel, [&] {
    a.emplace(a_path, read, rank, size);
    if (!one_file) b.emplace(b_path, read, rank, size);
    std::string payload;
    put(payload, encode(a->count()));
    if (!one_file) put(payload, encode(b->count()));
    return payload;
  });
  std::vector<std::vector<std::uint64_t>> a_counts, b_counts;
  for (const std::string& payload : counts) {
    Fields fields(payload);
    a_counts.push_back(decode(fields.next()));
    if (!one_file) b_counts.push_back(decode(fields.next()));
  }
  a->set_counts(a_counts);
  if (!one_file) b->set_counts(b_counts);

  // What every process now knows alike, so that all refuse alike: m >= n, the same rows in A and
  // B, B's columns fit for the method.
  const std::uint64_t m = a->rows();
  const Eigen::Index n_columns =
      one_file ? static_cast<Eigen::Index>(a->selected_columns().at(0).size()) : a->columns();
  const auto n = static_cast<std::uint64_t>(n_columns);
  const Eigen::Index d = one_file ? a->columns() - n_columns : b->columns();
  if (m < n) throw detail::fewer_samples_than_columns(a_path, m, n);
  if (!one_file) detail::check_same_rows(a_path, m, b_path, b->rows());
  detail::check_method_fits(method, one_file ? a_path : b_path, n_columns, d);
  // The noise model (every process has the options) against the data's sizes, and what the
  // method needs of it, alike on every process.
  if (auto refusal = detail::noise_refusal(options.noise, method)) {
    detail::throw_noise_refusal(*refusal, method, options.noise);
  }
  if (options.noise) static_cast<void>(options.noise->resolved(n_columns, d));

  const bool bootstrap = options.bootstrap > 0;
  // Too few groups for the Poisson scheme, and rows spread over processes cannot be resampled one
  // at a time in one memory: refused before the pass, alike on every process.
  if (bootstrap && m < static_cast<std::uint64_t>(detail::kBootstrapMinGroups * detail::kBootstrapGroupRows)) {
    throw io::DataError(a_path, 0, 0,
                        detail::too_few_groups(m, "under MPI the rows cannot be resampled one at a time in memory; "
                                                  "run on one process (without mpirun) for that"));
  }
  const std::vector<std::uint64_t> first =
      boundaries(m, size, bootstrap ? static_cast<std::uint64_t>(detail::kBootstrapGroupRows) : 1);
  for (int k = 0; k < size; ++k) out.rows_per_process.push_back(first[k + 1] - first[k]);
  const std::uint64_t my_first = first[static_cast<std::size_t>(rank)];
  const std::uint64_t my_rows = out.rows_per_process[static_cast<std::size_t>(rank)];

  // Where each process's rows start in each file (and so where the previous process's end).
  const std::vector<std::string> starts = step(channel, [&] {
    const LinePosition at_a = a->locate(my_first);
    const LinePosition at_b = one_file ? LinePosition{} : b->locate(my_first);
    return encode({at_a.byte, at_a.lines_before, at_b.byte, at_b.lines_before});
  });
  auto position = [&](int k, int file) -> LinePosition {
    if (k == size) return file == 0 ? a->locate(m) : b->locate(m);
    const std::vector<std::uint64_t> v = decode(starts[static_cast<std::size_t>(k)]);
    return {v[2 * file], v[2 * file + 1]};
  };

  // Each process's factors of its rows, the others stopping at their next block when one fails.
  PartFactors part;
  step(
      channel,
      [&] {
        StreamOptions mine = stream;
        mine.read = read;
        mine.progress = [&channel, user = stream.progress](double fraction) {
          if (channel.failure_announced()) throw StoppedByPartner();
          if (user) user(fraction);
        };
        if (my_rows == 0) {
          part.factors.total = TriangularFactor(n_columns, d, options.offsets != Offsets::None);
          part.factors.replicates.assign(static_cast<std::size_t>(options.bootstrap), part.factors.total);
          return std::string();
        }
        detail::PairReaders readers =
            one_file ? detail::PairReaders(a->open(my_first, my_rows, position(rank, 0), position(rank + 1, 0)),
                                           my_first)
                     : detail::PairReaders(a->open(my_first, my_rows, position(rank, 0), position(rank + 1, 0)),
                                           b->open(my_first, my_rows, position(rank, 1), position(rank + 1, 1)),
                                           my_first);
        readers.intercept = options.offsets != Offsets::None;
        if (bootstrap) {
          part.factors = detail::stream_resampled_factors(method, std::move(readers), mine, options.bootstrap,
                                                          options.seed);
        } else {
          part.factors.total = detail::stream_factor_for(method, std::move(readers), mine, &part.factors.info);
        }
        // The counting pass and the parser must agree on which lines are rows.
        if (part.factors.total.rows() != static_cast<Eigen::Index>(my_rows)) {
          throw std::logic_error("distributed fit: process " + std::to_string(rank) + " read " +
                                 std::to_string(part.factors.total.rows()) + " rows instead of " +
                                 std::to_string(my_rows));
        }
        return std::string();
      },
      true);

  merge_tree(channel, part);
  if (rank != 0) return out;
  if (std::optional<Warning> w = detail::streamed_sentinel_warning(part.factors.total)) {
    part.factors.info.warnings.push_back(std::move(*w));
  }
  out.result = bootstrap ? detail::fit_streamed_bootstrap(method, options, part.factors, a_path)
                         : detail::fit_streamed(method, options, part.factors.total, part.factors.info, a_path);
  return out;
}

DistributedFit fit_files_distributed(const std::string& a_path, const std::string& b_path,
                                     const FitRequest& request, Channel& channel) {
  const FitOptions options = request.resolved_options();
  return detail::naming_noise_files(request.noise_inputs, [&] {
    return fit_files_distributed(a_path, b_path, request.method, options, request.stream_options(),
                                 data_read_options(request, b_path), channel);
  });
}

}  // namespace spdfit
