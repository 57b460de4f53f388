#include "pipeline/pair_checks.hpp"

namespace spdfit::detail {

io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns) {
  return io::DataError(a_path, 0, 0,
                       "A has " + std::to_string(rows) + " rows (samples) but " + std::to_string(columns) +
                           " columns: at least as many samples as columns are needed");
}

void check_method_fits(const std::optional<Method>& method, const std::string& b_path, long long n, long long d) {
  if (!method) return;
  if (auto refusal = non_square_refusal(*method, n, d)) throw io::DataError(b_path, 0, 0, *refusal);
}

void check_enough_rows_for(Method method, const std::string& a_path, long long m, long long n, long long d) {
  if (auto refusal = too_few_rows_refusal(method, m, n, d)) throw io::DataError(a_path, 0, 0, *refusal);
}

}  // namespace spdfit::detail
