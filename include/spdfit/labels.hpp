// The names of a matrix's rows and columns as data files give them (a header row; pandas' and R's
// index column), and the renderings that show them: a labelled CSV table (`spdfit fit --header`,
// `spdfit nearest --header`) and a repair's JSON with its variables' names.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/render.hpp"

namespace spdfit {

namespace io {

/// A table and the labels of its rows: the first column of delimited text dropped as row labels
/// (ReadOptions::index_column), one per row; empty when there was none, and for other formats.
struct LabelledTable {
  Table table;
  std::vector<std::string> row_names;
};

/// read_table, keeping the labels of a dropped index column (pandas' df.cov().to_csv() names its
/// variables there and in the header). Throws as read_table does. Memory: the labels besides the
/// values, so meant for matrices rather than long logs.
LabelledTable read_labelled_table(const std::string& path, const ReadOptions& options = {});

}  // namespace io

/// The names of a square matrix's variables as its file gives them: the header row's column
/// names, else the labels of its index column; empty when it has neither, or when their count
/// is not the matrix's order. When both name the variables and differ, the header's are taken
/// and a warning naming `source` is appended to `warnings`.
std::vector<std::string> variable_names(const io::LabelledTable& file, const std::string& source,
                                        std::vector<Warning>* warnings);

/// X as a labelled CSV table, as pandas' to_csv and R's write.csv write one (io::write_csv with
/// names; pandas' read_csv(..., index_col=0) reads the labels back): rows named by `row_names`,
/// columns by `column_names`, each numbered from 1 instead when the names are not one per row
/// (column). Cost O(size of X).
std::string labelled_csv(const Eigen::MatrixXd& X, const std::vector<std::string>& row_names,
                         const std::vector<std::string>& column_names);
/// A fit's X: its rows named by A's columns and its columns by B's (row_names, column_names).
std::string labelled_csv(const FitResult& result);

/// A repair's JSON (to_json in spdfit/render.hpp) with `names`, the names of its variables, as the
/// key "names" when there are any.
std::string to_json(const NearestResult& result, const std::vector<std::string>& names,
                    JsonStyle style = JsonStyle::Contract);

}  // namespace spdfit
