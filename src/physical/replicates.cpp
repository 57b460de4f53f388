#include "physical/replicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "spdfit/random.hpp"

namespace spdfit::physical::detail {

namespace {

double quantile(const std::vector<double>& sorted, double q) {
  const double h = (static_cast<double>(sorted.size()) - 1.0) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

}  // namespace

EntrySummary summarize(Eigen::Index size, const std::vector<std::optional<Eigen::VectorXd>>& replicates,
                       double level) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EntrySummary out{Eigen::VectorXd::Constant(size, nan), Eigen::VectorXd::Constant(size, nan),
                   Eigen::VectorXd::Constant(size, nan)};
  std::vector<double> values;
  for (Eigen::Index i = 0; i < size; ++i) {
    values.clear();
    for (const auto& r : replicates) {
      if (r && std::isfinite((*r)(i))) values.push_back((*r)(i));
    }
    if (values.size() < 2) continue;
    double mean = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    double ss = 0.0;
    for (double v : values) ss += (v - mean) * (v - mean);
    out.standard_errors(i) = std::sqrt(ss / static_cast<double>(values.size() - 1));
    std::sort(values.begin(), values.end());
    out.lower(i) = quantile(values, 0.5 * (1.0 - level));
    out.upper(i) = quantile(values, 0.5 * (1.0 + level));
  }
  return out;
}

std::vector<std::uint32_t> resample_counts(Eigen::Index samples, std::uint64_t seed, std::size_t replicate) {
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(samples), 0);
  Random random(trial_seed(seed, replicate));
  const double n = static_cast<double>(samples);
  for (Eigen::Index draw = 0; draw < samples; ++draw) {
    const auto i = std::min(static_cast<Eigen::Index>(random.uniform() * n), samples - 1);
    ++counts[static_cast<std::size_t>(i)];
  }
  return counts;
}

}  // namespace spdfit::physical::detail
