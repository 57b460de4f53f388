// Internal: the check of a MATLAB 7.3 file (HDF5) that runs before libmatio reads it.
#pragma once

#include <cstdint>
#include <string>

namespace spdfit::io::detail {

/// Checks every dataset and attribute of a 7.3 .mat file that libmatio may read before it does:
/// none may declare more bytes (its points times its type's size, at least 16 bytes a point, what
/// a cell costs libmatio in a pointer and a reference) than kMaxExpansion times the file's
/// `file_size`. libmatio allocates them whole, a cell array's references while it only lists the
/// variables, and an HDF5 dataspace is a declared shape: a 3 kB file can declare 2^32 cells.
/// Throws DataError naming `file` and the object: "is a damaged .mat file (dataset '/c' declares
/// 4294967296 values of 8 bytes, more than the file can hold)". A file libhdf5 cannot open is
/// left to libmatio, which says so. Objects reached only through references, not through the
/// file's groups, are not visited (MATLAB links them all under /#refs#).
void check_mat73_structure(const std::string& file, std::uint64_t file_size);

}  // namespace spdfit::io::detail
