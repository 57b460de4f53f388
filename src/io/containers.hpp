// Internal: files that hold named arrays (MATLAB .mat through libmatio, NumPy .npz through
// libzip), the "file:name" way of naming one, and standard input ("-").
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

/// A data file and, for a .mat or .npz file, the array in it ("" when not named).
struct FileSpec {
  std::string file;
  std::string variable;
};

/// Splits "A.mat:accel" into the file and the array's name. A path that exists as given is a
/// file whatever its colons; otherwise the part before the last colon names the file when that
/// exists. Anything else is the path as given (whose reader then says "no such file").
FileSpec split_spec(const std::string& path);

/// Up to `count` first bytes of the file ("" when it cannot be read: its reader then says why).
std::string first_bytes(const std::string& path, std::size_t count);

/// All of standard input (for the file name "-"). Throws DataError naming "<stdin>" on a read
/// error or when it is empty.
std::string read_standard_input();

/// Whether the ZIP archive holds .npy entries (a NumPy .npz, not an .xlsx workbook).
bool holds_npy(const std::string& path);

/// Whether these first bytes of a file are a MATLAB .mat file (level 5, or 7.3 with its HDF5
/// body) or a ZIP archive (a NumPy .npz).
bool is_mat(std::string_view first);
bool is_zip(std::string_view first);
/// Whether they are a level-5 .mat file (not 7.3, whose body libhdf5 parses).
bool is_level5(std::string_view first);

/// The array `variable` of the .mat file (or, when it is "", the file's only 2-D numeric
/// array): double, single, integer and logical classes, converted to double; 1-D arrays are a
/// column. Throws DataError naming the file and variable: not a .mat file libmatio can read, no
/// such variable (listing those there are), several candidates and no name, a class or shape
/// that is not a real 2-D array, NaN or Inf (unless options allow them).
Table read_mat(const std::string& file, const std::string& variable, const ReadOptions& options);

/// The array `variable` ("x" or "x.npy") of the .npz file, or its only array when "" (several:
/// DataError listing them and the "file.npz:name" syntax). Compressed (savez_compressed) or not.
Table read_npz(const std::string& file, const std::string& variable, const ReadOptions& options);

/// Writes X to a level-5 .mat file as the double variable `name`. Throws DataError naming the
/// file when it cannot be written.
void write_mat(const std::string& file, const std::string& name, const Eigen::MatrixXd& X);

}  // namespace spdfit::io::detail
