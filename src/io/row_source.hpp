// Internal, included by row_reader.cpp only: the part of a RowReader that knows a file format
// (RowReader::Source; one kind per format: npy_source.hpp, text_source.hpp, whole_sources.hpp).
#pragma once

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "spdfit/row_reader.hpp"
#include "columns.hpp"
#include "containers.hpp"
#include "delimited_parser.hpp"
#include "file_error.hpp"
#include "kept_text.hpp"
#include "npy_layout.hpp"
#include "npy_rows.hpp"
#include "parse.hpp"
#include "read_file.hpp"
#include "split_file.hpp"

namespace spdfit::io {

using Eigen::Index;

struct RowReader::Source {
  explicit Source(std::string p) : path(std::move(p)) {}
  virtual ~Source() = default;
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;
  virtual Index read(Index max_rows, Eigen::MatrixXd* rows) = 0;
  virtual Index columns() const = 0;
  virtual const std::vector<std::string>& column_names() const { return no_names; }
  virtual const std::vector<Warning>& warnings() const { return no_warnings; }
  virtual double fraction_read() const = 0;
  virtual std::optional<std::uint64_t> rows_declared() const { return std::nullopt; }
  virtual const std::vector<std::vector<std::size_t>>& selected_columns() const { return selected; }

  // ReadOptions::columns for a format without names read a block at a time (.npy, MATLAB 7.3):
  // the whole rows are read into `full`, and the selected columns copied out in order.
  void select(const ReadOptions& options) {
    if (options.columns.empty()) return;
    const auto chosen =
        detail::resolve_columns(options.columns, {}, static_cast<std::size_t>(columns()), false, path);
    for (std::size_t c : detail::concatenated(chosen)) projection.push_back(static_cast<Index>(c));
    selected = detail::one_based(chosen);
  }

  std::string path;
  std::uint64_t rows_read = 0;
  std::vector<std::string> no_names;
  std::vector<Warning> no_warnings;
  std::vector<std::vector<std::size_t>> selected;
  std::vector<Index> projection;
  Eigen::MatrixXd full;
};

[[noreturn]] inline void fail_errno(const std::string& path, const std::string& doing) {
  throw DataError(path, 0, 0, doing + " (" + detail::describe_errno(errno) + ")");
}

}  // namespace spdfit::io
