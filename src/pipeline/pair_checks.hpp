// Internal: the checks every reader of a data pair A, B makes, with errors that name the files.
// Shared by the in-memory reader (fit_files.cpp) and the streaming one (stream.cpp).
#pragma once

#include <cstdint>
#include <string>

#include "spdfit/io.hpp"

namespace spdfit::detail {

/// The error for data A, read from `a_path`, with fewer rows (samples) than columns: an n x n
/// X needs at least n samples.
io::DataError fewer_samples_than_columns(const std::string& a_path, std::uint64_t rows, std::uint64_t columns);

}  // namespace spdfit::detail
