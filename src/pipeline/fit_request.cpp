// The fit's option table: each option declared once, with everything the front ends need.
#include "spdfit/fit_request.hpp"

#include <cstdint>
#include <limits>
#include <utility>

#include "spdfit/fit_files.hpp"

namespace spdfit {

namespace {

using Spec = OptionSpec<FitRequest>;

// The largest --block-rows: a block of 2^24 rows of a few columns is already hundreds of MB.
constexpr double kMaxBlockRows = double(std::int64_t{1} << 24);

double real(const OptionValue& v) { return std::get<double>(v); }
std::int64_t integer(const OptionValue& v) { return std::get<std::int64_t>(v); }
bool boolean(const OptionValue& v) { return std::get<bool>(v); }

std::vector<Spec> make_table() {
  std::vector<Spec> table;

  Spec rank;
  rank.name = "rank_tolerance";
  rank.cli = "--rank-tol";
  rank.python = "rank_tolerance";
  rank.type = OptionType::Real;
  rank.value_name = "NUMBER";
  rank.help = "Relative singular-value cut-off for numerical rank: sigma_i counts as zero when "
              "sigma_i <= tol * sigma_max, decided on A and B with their columns scaled to unit norm";
  rank.default_text = "max(m, n) eps";
  rank.range = {0.0, 1.0, false, true};
  rank.set = [](FitRequest& r, const OptionValue& v) { r.options.rank_tolerance = real(v); };
  rank.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    if (!r.options.rank_tolerance) return std::nullopt;
    return *r.options.rank_tolerance;
  };
  table.push_back(rank);

  Spec ratio;
  ratio.name = "noise_ratio";
  ratio.cli = "--noise-ratio";
  ratio.python = "noise_ratio";
  ratio.type = OptionType::Real;
  ratio.value_name = "NUMBER";
  ratio.help = "sigma_B / sigma_A, the noise in B relative to the noise in A, for the total least-squares "
               "methods (tls, tls-sym, tls-psd, spd-tls) and auto";
  ratio.default_text = "1";
  ratio.range = {0.0, std::numeric_limits<double>::infinity(), true, true};
  ratio.applies = [](const FitRequest& r) { return uses_noise_ratio(r.method); };
  ratio.applies_to = "the total least-squares methods and auto";
  ratio.set = [](FitRequest& r, const OptionValue& v) { r.options.noise_ratio = real(v); };
  ratio.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.noise_ratio; };
  table.push_back(ratio);

  Spec iterations;
  iterations.name = "max_iterations";
  iterations.cli = "--max-iter";
  iterations.python = "max_iter";
  iterations.type = OptionType::Integer;
  iterations.value_name = "N";
  iterations.help = "Iteration limit of spd-tls, psd-ls and auto; then the best iterate, with a warning";
  iterations.default_text = "200";
  iterations.range = {1.0, 1e6};
  iterations.applies = [](const FitRequest& r) { return uses_max_iterations(r.method); };
  iterations.applies_to = "the iterative methods";
  iterations.set = [](FitRequest& r, const OptionValue& v) { r.options.max_iterations = int(integer(v)); };
  iterations.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.max_iterations};
  };
  table.push_back(iterations);

  Spec floor;
  floor.name = "min_eig";
  floor.cli = "--min-eig";
  floor.python = "min_eig";
  floor.type = OptionType::Real;
  floor.value_name = "NUMBER";
  floor.help = "psd-ls: the floor epsilon of X >= epsilon I (0: positive semidefinite)";
  floor.default_text = "0";
  floor.range = {0.0, std::numeric_limits<double>::infinity()};
  floor.applies = [](const FitRequest& r) { return uses_min_eig(r.method); };
  floor.set = [](FitRequest& r, const OptionValue& v) { r.options.min_eig = real(v); };
  floor.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.min_eig; };
  table.push_back(floor);

  Spec bootstrap;
  bootstrap.name = "bootstrap";
  bootstrap.cli = "--bootstrap";
  bootstrap.python = "bootstrap";
  bootstrap.type = OptionType::Integer;
  bootstrap.value_name = "N";
  bootstrap.help = "Resample the rows N times for standard errors, a percentile interval and the bias of "
                   "every entry of X (auto: refitting the method it chose)";
  bootstrap.default_text = "0";
  bootstrap.range = {0.0, 1e7};
  bootstrap.set = [](FitRequest& r, const OptionValue& v) { r.options.bootstrap = int(integer(v)); };
  bootstrap.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.bootstrap};
  };
  bootstrap.nullable = false;
  table.push_back(bootstrap);

  Spec confidence;
  confidence.name = "confidence";
  confidence.cli = "--confidence";
  confidence.python = "confidence";
  confidence.type = OptionType::Real;
  confidence.value_name = "FRACTION";
  confidence.help = "The bootstrap intervals' level, a fraction";
  confidence.default_text = "0.95";
  confidence.range = {0.0, 1.0, true, true};
  confidence.needs = {"bootstrap"};
  confidence.needs_message = "`confidence` applies to the bootstrap: give `bootstrap` N as well";
  confidence.set = [](FitRequest& r, const OptionValue& v) { r.options.confidence = real(v); };
  confidence.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.confidence; };
  table.push_back(confidence);

  Spec seed;
  seed.name = "seed";
  seed.cli = "--seed";
  seed.python = "seed";
  seed.type = OptionType::Integer;
  seed.value_name = "N";
  seed.help = "The bootstrap's seed; the numbers depend on nothing else";
  seed.default_text = "1";
  seed.range = {0.0, double(std::numeric_limits<std::int64_t>::max())};
  seed.needs = {"bootstrap"};
  seed.needs_message = "`seed` applies to the bootstrap: give `bootstrap` N as well";
  seed.set = [](FitRequest& r, const OptionValue& v) { r.options.seed = std::uint64_t(integer(v)); };
  seed.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return static_cast<std::int64_t>(r.options.seed);
  };
  table.push_back(seed);

  Spec threads;
  threads.name = "threads";
  threads.cli = "--threads";
  threads.python = "threads";
  threads.type = OptionType::Integer;
  threads.value_name = "N";
  threads.help = "Threads for streaming and the bootstrap (0: one per core); the result does not depend on it";
  threads.default_text = "0";
  threads.range = {0.0, 1024.0};
  threads.needs = {"stream", "bootstrap"};
  threads.needs_message = "`threads` applies to `stream` and `bootstrap`: give one of them, or leave `threads` out";
  threads.set = [](FitRequest& r, const OptionValue& v) { r.options.threads = unsigned(integer(v)); };
  threads.get = [](const FitRequest& r) -> std::optional<OptionValue> {
    return std::int64_t{r.options.threads};
  };
  threads.nullable = false;
  table.push_back(threads);

  Spec reported;
  reported.name = "reported_diagnostics";
  reported.python = "reported_diagnostics";
  reported.type = OptionType::Boolean;
  reported.help = "False skips the diagnostics that neither X nor a warning needs, at large n most of the time "
                  "beyond the estimate: noise_sigma and area_criterion are then None, residual_norm and "
                  "cond_b_scaled 0, and cond_a_scaled 0 unless A may be ill-conditioned enough for its warning";
  reported.default_text = "True";
  reported.set = [](FitRequest& r, const OptionValue& v) { r.options.reported_diagnostics = boolean(v); };
  reported.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.options.reported_diagnostics; };
  reported.nullable = false;
  table.push_back(reported);

  Spec stream;
  stream.name = "stream";
  stream.cli = "--stream";
  stream.type = OptionType::Flag;
  stream.help = "Read A and B a block of rows at a time (memory O(threads x block-rows x n + n^2) whatever the "
                "number of rows; same estimate to rounding)";
  stream.set = [](FitRequest& r, const OptionValue& v) { r.stream = boolean(v); };
  stream.get = [](const FitRequest& r) -> std::optional<OptionValue> { return r.stream; };
  stream.nullable = false;
  table.push_back(stream);

  Spec block;
  block.name = "block_rows";
  block.cli = "--block-rows";
  block.python = "block_rows";
  block.type = OptionType::Integer;
  block.value_name = "N";
  block.help = "Rows per block when streaming";
  block.default_text = "32768";
  block.range = {1.0, kMaxBlockRows};
  block.needs = {"stream"};
  block.set = [](FitRequest& r, const OptionValue& v) { r.block_rows = Eigen::Index(integer(v)); };
  block.get = [](const FitRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.block_rows}; };
  block.nullable = false;
  table.push_back(block);

  return table;
}

}  // namespace

StreamOptions FitRequest::stream_options() const {
  StreamOptions stream;
  stream.block_rows = block_rows;
  stream.threads = options.threads;
  stream.read = read;
  stream.progress = read_progress;
  return stream;
}

const std::vector<OptionSpec<FitRequest>>& fit_option_table() {
  static const std::vector<OptionSpec<FitRequest>> table = make_table();
  return table;
}

bool FitRequest::is_valid(std::string* error) const { return options_in_range(*this, fit_option_table(), error); }

bool FitOptions::is_valid(std::string* error) const {
  if (noise && noise_ratio != 1.0) {
    if (error) {
      *error = "`noise_ratio` cannot be combined with a noise model (" + noise->option_a() + ", " +
               noise->option_b() + "): the noise model gives the noise in A and in B, and so their ratio";
    }
    return false;
  }
  FitRequest request;
  request.options = *this;
  request.options.progress = nullptr;  // a copy of the options' numbers only
  request.options.noise.reset();       // the table checks the numbers; the model checked itself
  return request.is_valid(error);
}

void check_fit_request(const FitRequest& request, const std::vector<std::string_view>& given) {
  std::vector<std::pair<std::string, FitRequest>> methods;
  for (Method m : kSelectableMethods) {
    FitRequest other;
    other.method = m;
    methods.emplace_back(std::string(to_string(m)), other);
  }
  for (std::string_view name : given) {
    const OptionSpec<FitRequest>* spec = find_option(fit_option_table(), name);
    if (spec == nullptr) continue;
    if (auto why = misplaced_option(*spec, request, methods, to_string(request.method))) throw OptionError(*why);
  }
  check_option_combination(fit_option_table(), given);
}

FitResult fit_files(const std::string& a_path, const std::string& b_path, const FitRequest& request) {
  std::optional<StreamOptions> stream;
  if (request.stream) stream = request.stream_options();
  return fit_files(a_path, b_path, request.method, request.options, stream, request.read);
}

}  // namespace spdfit
