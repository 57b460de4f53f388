// The fit's request: its options resolved (the noise model from its sources), and the fit of files.
#include "spdfit/fit_request.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "io/row_selection.hpp"
#include "pipeline/log_rows.hpp"
#include "robust/m_estimator.hpp"
#include "pipeline/noise_files.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/noise_model.hpp"

namespace spdfit {

StreamOptions FitRequest::stream_options() const {
  StreamOptions stream;
  stream.block_rows = block_rows;
  stream.threads = options.threads;
  stream.read = read;
  stream.progress = read_progress;
  return stream;
}

FitOptions FitRequest::resolved_options() const {
  if (noise_inputs.empty()) return options;
  if (options.noise) {
    throw OptionError("give the noise model as `noise` or as its files and numbers, not both");
  }
  FitOptions out = options;
  const NoiseInputs& in = noise_inputs;
  // A matrix given as a file or as values (MATLAB's; the command line's numbers in one row).
  const auto values = [this](const MatrixInput& m) { return m.from_file() ? io::read_matrix(m.path, read) : m.values; };
  if (in.rest_a.given() || in.rest_b.given()) {
    if (!in.rest_a.given() || !in.rest_b.given()) {
      throw OptionError("`rest_a` and `rest_b` come together", Code::OptionConflict, "rest_a");
    }
    // One log's column selections choose the rest files' columns too: A's of rest_a, B's of rest_b.
    const io::ReadOptions rest_read = detail::log_columns_read(*this);
    const auto rest_values = [&](const MatrixInput& m, std::size_t side) {
      if (!m.from_file() || rest_read.columns.empty()) return values(m);
      io::ReadOptions one = rest_read;
      one.columns = {rest_read.columns[side]};
      return io::read_matrix(m.path, one);
    };
    if (in.rest_a.from_file() && in.rest_b.from_file()) {
      out.noise = NoiseModel::from_rest_files(in.rest_a.path, in.rest_b.path, rest_read, block_rows);
    } else {
      const Eigen::MatrixXd rest_a = rest_values(in.rest_a, 0), rest_b = rest_values(in.rest_b, 1);
      out.noise = detail::naming_noise_files(in, [&] { return NoiseModel::from_rest(rest_a, rest_b); });
    }
  } else if (!in.std_a.empty() || !in.std_b.empty()) {
    const auto vector = [](const std::vector<double>& v) {
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
    };
    out.noise = NoiseModel::from_std(vector(in.std_a), vector(in.std_b));
  } else {
    if (!in.cov_a.given() || !in.cov_b.given()) {
      throw OptionError("`noise_cov_a` and `noise_cov_b` come together", Code::OptionConflict, "noise_cov_a");
    }
    const Eigen::MatrixXd cov_a = values(in.cov_a);
    const Eigen::MatrixXd cov_b = values(in.cov_b);
    out.noise = detail::naming_noise_files(in, [&] { return NoiseModel::from_cov(cov_a, cov_b); });
  }
  return out;
}

FitOptions FitRequest::resolved_options(Eigen::Index n, Eigen::Index d) const {
  FitOptions out = resolved_options();
  if (out.noise) out.noise = detail::naming_noise_files(noise_inputs, [&] { return out.noise->resolved(n, d); });
  return out;
}

io::ReadOptions data_read_options(const FitRequest& request, const std::string& b_path) {
  io::ReadOptions read = detail::log_columns_read(request);
  if (!read.columns.empty() && !b_path.empty()) {
    throw OptionError("`a_cols` and `b_cols` choose A and B from one file, but two files were given (" + b_path +
                      " as B's)");
  }
  return read;
}

FitResult fit_files(const std::string& a_path, const std::string& b_path, const FitRequest& request) {
  const io::ReadOptions read = data_read_options(request, b_path);
  std::optional<StreamOptions> stream;
  if (request.stream) stream = request.stream_options();
  const FitOptions options = request.resolved_options();
  if (!request.rows.empty() || !request.rest_rows.empty() || !request.time_col.empty()) {
    if (request.stream) {
      throw OptionError("`rows` and `rest_rows` choose rows of a log fitted in memory, not streamed: leave out "
                        "`stream` (and mpirun), or cut the files first",
                        Code::OptionConflict, request.rows.empty() ? "rest_rows" : "rows");
    }
    // The fit refuses a noise model its method cannot use (data_of), as for rest files.
    DataPair data = read_pair(a_path, b_path, read);
    FitOptions log_options = options;
    detail::RowNumbers numbers;
    const std::vector<Warning> found = detail::apply_log_rows(request, data.A, data.B, a_path, log_options, &numbers);
    data.warnings.insert(data.warnings.end(), found.begin(), found.end());
    return detail::fit_pair_in_memory(std::move(data), a_path, b_path, request.method, log_options, numbers);
  }
  return detail::naming_noise_files(request.noise_inputs, [&] {
    return fit_files(a_path, b_path, request.method, options, stream, read);
  });
}

}  // namespace spdfit
