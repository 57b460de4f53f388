// Internal: the parsers behind io::read_table, on bytes already in memory. Used by the readers in
// src/io, the linkage pairs file, and the unit tests and fuzz targets (which include src/).
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "spdfit/io.hpp"

namespace spdfit::io {

/// read_table on bytes already in memory: a .npy file when they start with the .npy magic bytes,
/// delimited text otherwise. `source` names them in errors. Throws DataError as read_table does
/// (empty bytes: "file is empty").
Table parse_table(std::string_view bytes, const std::string& source, const ReadOptions& options = {});

/// The two parsers behind parse_table; `source` names the bytes in errors.
Table parse_delimited(std::string_view text, const std::string& source, const ReadOptions& options = {});
Eigen::MatrixXd parse_npy(std::string_view bytes, const std::string& source, const ReadOptions& options = {});

}  // namespace spdfit::io
