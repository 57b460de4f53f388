#include "spdfit/experiment/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace spdfit::experiment {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Mean and sample variance by Welford's update (stable for large means).
struct Moments {
  std::size_t count = 0;
  double mean = 0.0, m2 = 0.0;
  void add(double x) {
    ++count;
    const double delta = x - mean;
    mean += delta / static_cast<double>(count);
    m2 += delta * (x - mean);
  }
  double std() const { return count > 1 ? std::sqrt(m2 / static_cast<double>(count - 1)) : 0.0; }
};

}  // namespace

double Summary::standard_error() const {
  return count > 0 ? std / std::sqrt(static_cast<double>(count)) : kNaN;
}

Summary summarize(std::vector<double> values) {
  Summary s;
  const auto finite_end =
      std::partition(values.begin(), values.end(), [](double x) { return !std::isnan(x); });
  s.failures = static_cast<std::size_t>(values.end() - finite_end);
  values.erase(finite_end, values.end());
  s.count = values.size();
  if (values.empty()) {
    s.mean = s.std = s.median = s.min = s.max = kNaN;
    return s;
  }
  Moments moments;
  for (double x : values) moments.add(x);
  s.mean = moments.mean;
  s.std = moments.std();
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  s.min = *lo;
  s.max = *hi;
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  s.median = values[middle];
  if (values.size() % 2 == 0) {
    s.median = 0.5 * (s.median + *std::max_element(values.begin(), values.begin() + middle));
  }
  return s;
}

const char* to_string(Order order) {
  switch (order) {
    case Order::Lower:
      return "lower";
    case Order::Tie:
      return "tie";
    case Order::Higher:
      return "higher";
  }
  return "unknown";
}

Order order_of(const PairedComparison& c, double significance) {
  if (c.mean_difference + significance * c.standard_error < 0) return Order::Lower;
  if (c.mean_difference - significance * c.standard_error > 0) return Order::Higher;
  return Order::Tie;
}

PairedComparison compare_paired(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("compare_paired: the samples differ in length");
  Moments moments;
  std::size_t lower = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::isnan(a[k]) || std::isnan(b[k])) continue;
    moments.add(a[k] - b[k]);
    if (a[k] < b[k]) ++lower;
  }
  PairedComparison c;
  c.count = moments.count;
  if (c.count == 0) {
    c.mean_difference = c.standard_error = c.fraction_lower = kNaN;
    return c;
  }
  c.mean_difference = moments.mean;
  c.standard_error = moments.std() / std::sqrt(static_cast<double>(c.count));
  c.fraction_lower = static_cast<double>(lower) / static_cast<double>(c.count);
  return c;
}

std::vector<std::pair<Eigen::Index, Eigen::Index>> upper_triangle_entries(Eigen::Index n) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> entries;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i; j < n; ++j) entries.emplace_back(i, j);
  return entries;
}

EntryStatistics summarize_entries(Method method, Eigen::MatrixXd errors) {
  EntryStatistics s;
  s.method = method;
  const Eigen::Index entries = errors.cols();
  std::vector<Moments> signed_moments(entries), absolute_moments(entries);
  for (Eigen::Index k = 0; k < errors.rows(); ++k) {
    if (errors.row(k).hasNaN()) {
      ++s.failures;
      continue;
    }
    ++s.count;
    for (Eigen::Index e = 0; e < entries; ++e) {
      signed_moments[e].add(errors(k, e));
      absolute_moments[e].add(std::abs(errors(k, e)));
    }
  }
  s.mae.resize(entries);
  s.std.resize(entries);
  s.bias.resize(entries);
  for (Eigen::Index e = 0; e < entries; ++e) {
    s.mae(e) = s.count ? absolute_moments[e].mean : kNaN;
    s.bias(e) = s.count ? signed_moments[e].mean : kNaN;
    s.std(e) = s.count ? signed_moments[e].std() : kNaN;
  }
  s.errors = std::move(errors);
  return s;
}

}  // namespace spdfit::experiment
