#include "pipeline/pair_checks.hpp"

namespace spdfit::detail {

io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns) {
  return io::DataError(a_path, 0, 0,
                       "A has " + std::to_string(rows) + " rows (samples) but " + std::to_string(columns) +
                           " columns: at least as many samples as columns are needed");
}

}  // namespace spdfit::detail
