#include "pipeline/pair_checks.hpp"

#include <stdexcept>

namespace spdfit::detail {

io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns) {
  return io::DataError(a_path, 0, 0,
                       "A has " + std::to_string(rows) + " rows (samples) but " + std::to_string(columns) +
                           " columns: at least as many samples as columns are needed");
}

std::string rows_text(std::uint64_t rows) { return std::to_string(rows) + (rows == 1 ? " row" : " rows"); }

io::DataError unequal_rows(const std::string& b_path, const std::string& problem) {
  return io::DataError(b_path, 0, 0, problem + ": A and B must have the same numbers of rows (samples)",
                       Code::DataShape);
}

void check_same_rows(const std::string& a_path, std::uint64_t rows_a, const std::string& b_path,
                     std::uint64_t rows_b) {
  if (rows_a == rows_b) return;
  throw unequal_rows(b_path, "B has " + rows_text(rows_b) + " but A (" + a_path + ") has " + std::to_string(rows_a));
}

void check_method_fits(const std::optional<Method>& method, const std::string& b_path, long long n, long long d) {
  if (!method) return;
  if (auto refusal = non_square_refusal(*method, n, d)) throw io::DataError(b_path, 0, 0, *refusal);
}

void check_enough_rows_for(Method method, const std::string& a_path, long long m, long long n, long long d) {
  if (auto refusal = too_few_rows_refusal(method, m, n, d)) throw io::DataError(a_path, 0, 0, *refusal);
}

}  // namespace spdfit::detail

namespace spdfit::detail {

const io::ReadOptions& checked_pair_read(const std::string& b_path, const io::ReadOptions& read) {
  if (b_path.empty() && read.columns.size() != 2) {
    throw std::invalid_argument("A and B from one file need two column selections (`a_cols` and `b_cols`)");
  }
  if (!b_path.empty() && !read.columns.empty()) {
    throw std::invalid_argument("`a_cols` and `b_cols` choose A and B from one file, but B's file (" + b_path +
                                ") was given too");
  }
  return read;
}

SelectionSplit split_selection(const std::string& path, const std::vector<std::string>& names,
                               const std::vector<std::vector<std::size_t>>& selected) {
  SelectionSplit out;
  if (selected.size() != 2) return out;
  const std::size_t n = selected[0].size();
  if (names.size() == n + selected[1].size()) {
    out.a_names.assign(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(n));
    out.b_names.assign(names.begin() + static_cast<std::ptrdiff_t>(n), names.end());
  }
  const std::string file = path == "-" ? std::string("standard input") : path;
  out.a_columns = file + " " + io::describe_columns(selected[0], out.a_names);
  out.b_columns = file + " " + io::describe_columns(selected[1], out.b_names);
  return out;
}

}  // namespace spdfit::detail
