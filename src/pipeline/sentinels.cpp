// The warning about loggers' codes for invalid readings in A and B.
#include "pipeline/sentinels.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace spdfit::detail {

namespace {

// Rows named in the warning; the count says how many more.
constexpr std::size_t kNamedRows = 5;

struct Sentinel {
  Eigen::Index row;
  bool in_a;
  Eigen::Index column;
  double value;
};

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// The rows to keep, as ranges of 1-based row numbers in the file ("1:16,18:50", as `rows` takes
// them), when short: runs of consecutive numbers among the rows of A and B that are not left out.
std::string kept_rows(Eigen::Index m, const std::vector<Eigen::Index>& left_out, const RowNumbers& numbers) {
  std::string out;
  std::size_t ranges = 0, next = 0;
  std::uint64_t first = 0, last = 0;  // the current run, 1-based; first == 0: none
  const auto close = [&] {
    if (first == 0) return;
    out += (ranges == 0 ? "" : ",") + std::to_string(first) +
           (last > first ? ":" + std::to_string(last) : std::string());
    ++ranges;
    first = 0;
  };
  for (Eigen::Index i = 0; i < m; ++i) {
    if (next < left_out.size() && left_out[next] == i) {
      ++next;
      close();
      continue;
    }
    const std::uint64_t row = file_row(numbers, i);
    if (first != 0 && row != last + 1) close();
    if (first == 0) first = row;
    last = row;
  }
  close();
  if (ranges == 0 || ranges > 6) return std::string();
  return out;
}

}  // namespace

std::vector<Eigen::Index> sentinel_rows(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B) {
  std::vector<Eigen::Index> rows;
  const bool with_b = B.rows() == A.rows();
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    if ((A.row(i).cwiseAbs().array() >= kSentinelMagnitude).any() ||
        (with_b && (B.row(i).cwiseAbs().array() >= kSentinelMagnitude).any())) {
      rows.push_back(i);
    }
  }
  return rows;
}

std::optional<Warning> sentinel_warning(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B, const RowNumbers& numbers,
                                        bool robust) {
  const std::vector<Eigen::Index> rows = sentinel_rows(A, B);
  const Eigen::Index m = A.rows();
  // The first few rows' first such value: A's columns, then B's.
  std::vector<Sentinel> found;
  for (std::size_t k = 0; k < rows.size() && k < kNamedRows; ++k) {
    const Eigen::Index i = rows[k];
    for (Eigen::Index j = 0; j < A.cols() + B.cols(); ++j) {
      const bool in_a = j < A.cols();
      const double v = in_a ? A(i, j) : B(i, j - A.cols());
      if (!(std::abs(v) >= kSentinelMagnitude)) continue;
      found.push_back({i, in_a, in_a ? j : j - A.cols(), v});
      break;
    }
  }
  if (rows.empty()) return std::nullopt;
  std::string named;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const Sentinel& s = found[k];
    named += (k == 0 ? "" : ", ") + std::to_string(file_row(numbers, s.row)) + " (" + number(s.value) + " in " +
             (s.in_a ? "A" : "B") + "'s column " + std::to_string(s.column + 1) + ")";
  }
  const bool one = rows.size() == 1;
  std::string text = (one ? "row " : "rows ") + named;
  if (rows.size() > found.size()) text += " and " + std::to_string(rows.size() - found.size()) + " more";
  text += (one ? " holds" : " hold");
  if (robust) {
    text += " a value of magnitude 1e30 or more: a logger's code for an invalid reading, not a measurement; the "
            "robust fit gave " + std::string(one ? "it" : "them") + " weight 0";
    return Warning(Code::Outliers, text, "rows");
  }
  text += " a value of magnitude 1e30 or more: a logger's code for an invalid reading, not a measurement, and " +
          std::string(one ? "it dominates" : "they dominate") +
          " the fit (and A's and B's singular values, ranks and condition numbers); leave " +
          (one ? "it" : "them") + " out of A and B";
  const std::string kept = kept_rows(m, rows, numbers);
  if (!kept.empty()) text += " (the rows " + kept + ", as --rows takes them without --time-col)";
  return Warning(Code::Outliers, text, "rows");
}

std::optional<Warning> streamed_sentinel_warning(const TriangularFactor& factor) {
  // |x| < 2^e for every entry: a sentinel of 1e30 or more makes e at least 100.
  constexpr int kSentinelExponent = 100;
  const bool in_a = factor.exponent_a() >= kSentinelExponent, in_b = factor.exponent_b() >= kSentinelExponent;
  if (!in_a && !in_b) return std::nullopt;
  const std::string where = in_a && in_b ? "A and B hold" : in_a ? "A holds" : "B holds";
  return Warning(Code::Outliers,
                 where + " a value of magnitude about 1e30 or more: a logger's code for an invalid reading, not a "
                         "measurement, and it dominates the fit (and A's and B's singular values, ranks and condition "
                         "numbers); the streamed fit keeps no rows to name: fit in memory (without `stream`) to have "
                         "its rows named, and leave them out of A and B",
                 "rows");
}

}  // namespace spdfit::detail
