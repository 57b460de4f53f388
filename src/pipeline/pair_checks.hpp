// Internal: the checks every reader of a data pair A, B makes, with errors that name the files.
// Shared by the in-memory reader (fit_files.cpp) and the streaming one (stream.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "spdfit/io.hpp"
#include "spdfit/method.hpp"

namespace spdfit::detail {

/// The error for data A, read from `a_path`, with fewer rows (samples) than columns: an n x n
/// X needs at least n samples.
io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns);

/// Throws io::DataError, naming B's file, when A has n columns and B d != n and `method` (when
/// given) needs a square X (non_square_refusal).
void check_method_fits(const std::optional<Method>& method, const std::string& b_path, long long n, long long d);

/// Throws io::DataError, naming A's file, when m rows are too few for `method`
/// (too_few_rows_refusal).
void check_enough_rows_for(Method method, const std::string& a_path, long long m, long long n, long long d);

}  // namespace spdfit::detail
