// Which data files hold named arrays (MATLAB .mat, NumPy .npz), the files that "file:name" and
// `--var-a NAME` pick an array of.
#pragma once

#include <string>

namespace spdfit::io {

/// Whether `file` holds named arrays, judged by its content as read_table judges it: a MATLAB .mat
/// file or a NumPy .npz archive. False for standard input ("-"), text, .npy files and files that
/// cannot be opened (whose reader then says why). Cost: reads the file's first bytes.
bool holds_named_arrays(const std::string& file);

}  // namespace spdfit::io
