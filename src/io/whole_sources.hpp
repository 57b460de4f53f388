// Internal, included by row_reader.cpp only: a MATLAB 7.3 variable read in slabs, and files read whole
// (.mat, .npz, .npy on standard input) handed out a block of rows at a time.
#pragma once

#include "row_source.hpp"

namespace spdfit::io {

using Eigen::Index;

// A variable of a MATLAB 7.3 file (HDF5), read a block of rows at a time. libmatio opens the
// dataset anew for each read, and so decompresses each chunk anew: it is read in slabs of about
// 8 MB (or the block, if larger), which the blocks are cut from.
class RowReader::MatSource final : public RowReader::Source {
 public:
  MatSource(const std::string& path, const detail::FileSpec& spec, const ReadOptions& options)
      : Source(path), blocks_(spec), options_(options) {
    select(options);
  }
  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    const auto count = static_cast<Index>(
        std::min<std::uint64_t>(blocks_.rows() - rows_read, static_cast<std::uint64_t>(max_rows)));
    if (rows_read + static_cast<std::uint64_t>(count) > slab_first_ + static_cast<std::uint64_t>(slab_.rows())) {
      const Index slab_rows = std::max<Index>(count, kSlabBytes / (8 * std::max<Index>(1, blocks_.columns())));
      slab_first_ = rows_read;
      blocks_.read(slab_first_,
                   static_cast<Index>(std::min<std::uint64_t>(blocks_.rows() - slab_first_,
                                                              static_cast<std::uint64_t>(slab_rows))),
                   &slab_);
    }
    *rows = slab_.middleRows(static_cast<Index>(rows_read - slab_first_), count);
    if (!options_.allow_nonfinite) detail::check_npy_finite(*rows, rows_read, blocks_.name());
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  Index columns() const override { return blocks_.columns(); }
  double fraction_read() const override {
    return static_cast<double>(rows_read) / static_cast<double>(blocks_.rows());
  }
  std::optional<std::uint64_t> rows_declared() const override { return blocks_.rows(); }

 private:
  static constexpr Index kSlabBytes = Index{8} << 20;
  detail::MatRowBlocks blocks_;
  ReadOptions options_;
  Eigen::MatrixXd slab_;
  std::uint64_t slab_first_ = 0;
};

// A .mat or .npz file, or a .npy file on standard input, read whole (their libraries read whole
// arrays; a pipe cannot be mapped) and handed out a block at a time, with a warning on memory.
class RowReader::TableSource final : public RowReader::Source {
 public:
  TableSource(const std::string& path, Table table) : Source(path), table_(std::move(table)) {
    table_.warnings.push_back(Warning(Code::FileNotice, 
        (path == "-" ? std::string("standard input") : path) +
        " is read whole, not a block at a time (text, MATLAB 7.3 files and .npy files named by path are "
        "streamed; .npz, older .mat files and .npy on standard input are not): memory grows with its rows"));
  }
  Index read(Index max_rows, Eigen::MatrixXd* rows) override {
    const Index left = table_.values.rows() - static_cast<Index>(rows_read);
    const Index count = std::min(max_rows, left);
    *rows = table_.values.middleRows(static_cast<Index>(rows_read), count);
    rows_read += static_cast<std::uint64_t>(count);
    return count;
  }
  Index columns() const override { return table_.values.cols(); }
  std::optional<std::uint64_t> rows_declared() const override {
    return static_cast<std::uint64_t>(table_.values.rows());
  }
  double fraction_read() const override {
    return static_cast<double>(rows_read) / static_cast<double>(table_.values.rows());
  }
  const std::vector<std::string>& column_names() const override { return table_.column_names; }
  const std::vector<Warning>& warnings() const override { return table_.warnings; }
  const std::vector<std::vector<std::size_t>>& selected_columns() const override {
    return table_.selected_columns;
  }

 private:
  Table table_;
};

}  // namespace spdfit::io
