// Internal: files that hold named arrays (MATLAB .mat through libmatio, NumPy .npz through
// libzip), the "file:name" way of naming one, and standard input ("-").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

// The public "file:name" rule (io.hpp), by its internal names.
using io::FileSpec;
using io::split_spec;

/// How messages name standard input (the file name "-").
inline constexpr const char* kStdinName = "<stdin>";

/// Standard input after `bytes` (what was read from it already), up to `at_most` bytes in all.
/// Throws DataError naming kStdinName on a read error or when it is empty.
std::string read_standard_input(std::string bytes = {}, std::size_t at_most = static_cast<std::size_t>(-1));

/// Up to `count` first bytes of the file ("" when it cannot be read: its reader then says why).
std::string first_bytes(const std::string& path, std::size_t count);

/// The file's size in bytes (0 when it cannot be read).
std::uint64_t file_size(const std::string& path);

/// Names for a message, comma-separated, the first 20 and how many in all.
std::string listed_names(const std::vector<std::string>& names);

/// Whether these first bytes of a file are a MATLAB .mat file's header (level 5 or 7.3).
bool is_mat(std::string_view first);

/// Whether the ZIP archive `path` holds .npy entries (a NumPy .npz, not an .xlsx workbook).
bool holds_npy(const std::string& path);

/// Whether these first bytes of a file are a level-5 MATLAB .mat file (not 7.3, whose body
/// libhdf5 parses): the files whose structure read_mat checks before libmatio reads them.
bool is_level5(std::string_view first);

/// The array `variable` of the .mat file (or, when it is "", the file's only 2-D numeric
/// array): double, single, integer and logical classes, converted to double; 1-D arrays are a
/// column. Throws DataError naming the file and variable: not a .mat file libmatio can read, no
/// such variable (listing those there are), several candidates and no name, a class or shape
/// that is not a real 2-D array, NaN or Inf (unless options allow them).
Table read_mat(const std::string& file, const std::string& variable, const ReadOptions& options);

/// A 7.3 .mat file's variable (chosen as read_mat chooses it, with its checks), read a block of
/// rows at a time: HDF5 hyperslabs through libmatio, so that memory does not grow with its rows.
class MatRowBlocks {
 public:
  explicit MatRowBlocks(const FileSpec& spec);
  ~MatRowBlocks();
  MatRowBlocks(const MatRowBlocks&) = delete;
  MatRowBlocks& operator=(const MatRowBlocks&) = delete;

  std::uint64_t rows() const;
  Eigen::Index columns() const;
  const std::string& name() const;  ///< "file" or "file:variable", as messages name it
  /// Rows [first, first + count), converted to double (NaN and Inf not checked).
  void read(std::uint64_t first, Eigen::Index count, Eigen::MatrixXd* out);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The array `variable` ("x" or "x.npy") of the .npz file, or its only array when "" (several:
/// DataError listing them and the "file.npz:name" syntax). Compressed (savez_compressed) or not.
Table read_npz(const std::string& file, const std::string& variable, const ReadOptions& options);

/// Which files hold named arrays, decided by their first bytes (a .npz is a zip archive of .npy
/// files): the one place that decides it, for read_named_arrays and for splitting files.
enum class NamedArrays { None, Mat, Mat73, Npz };
NamedArrays named_arrays_kind(const FileSpec& spec);

/// The table of a .mat or .npz file (read_mat, read_npz), decided by named_arrays_kind; nothing
/// for any other file (and for standard input). The one place that decides which files hold
/// named arrays, for read_table and RowReader.
std::optional<Table> read_named_arrays(const FileSpec& spec, const ReadOptions& options);

}  // namespace spdfit::io::detail
