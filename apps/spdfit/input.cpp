#include "input.hpp"

#include "spdfit/io.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Eigen::MatrixXd load_matrix(const std::string& path, const GlobalOptions& global) {
  io::Table table = io::read_table(path, global.read);
  for (const std::string& w : table.warnings) warn(global, w);
  return std::move(table.values);
}

io::ReadOptions data_read(const FitRequest& request, const std::string& b_path) {
  if (b_path.empty() && request.a_cols.empty() && request.b_cols.empty()) {
    throw UsageError("B's file is missing: give the files of A and B, or one file with --a-cols and --b-cols "
                     "choosing their columns");
  }
  try {
    return data_read_options(request, b_path);
  } catch (const OptionError& e) {
    throw_usage(e);
  } catch (const io::ColumnSelectionError& e) {
    throw_usage(e);
  }
}

DataPair load_pair(const std::string& a_path, const std::string& b_path, const FitRequest& request,
                   const GlobalOptions& global) {
  const io::ReadOptions read = data_read(request, b_path);
  DataPair data;
  try {
    data = read_pair(a_path, b_path, read);
  } catch (const io::ColumnSelectionError& e) {
    throw_usage(e);
  }
  for (const std::string& w : data.warnings) warn(global, w);
  return data;
}

}  // namespace spdfit::cli
