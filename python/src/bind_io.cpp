// Reading and writing data files from Python.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "spdfit/io.hpp"

namespace py = pybind11;

namespace spdfit::python {

void bind_io(py::module_& m) {

  // (values, column_names, warnings); index_col None: decided from the file, True: drop the
  // first column (row labels), False: it is data (io::IndexColumn); header likewise for the first
  // line (io::HeaderRow).
  m.def(
      "read_table",
      [](const std::string& path, bool allow_nonfinite, std::optional<bool> index_col, std::optional<bool> header) {
        io::ReadOptions options;
        options.allow_nonfinite = allow_nonfinite;
        if (index_col) options.index_column = *index_col ? io::IndexColumn::Drop : io::IndexColumn::Keep;
        if (header) options.header_row = *header ? io::HeaderRow::Present : io::HeaderRow::Absent;
        io::Table table;
        {
          py::gil_scoped_release release;
          table = io::read_table(path, options);
        }
        return py::make_tuple(table.values, table.column_names, table.warnings);
      },
      py::arg("path"), py::kw_only(), py::arg("allow_nonfinite") = false, py::arg("index_col") = py::none(),
      py::arg("header") = py::none(),
      "The matrix, column names and reader warnings of a data file (spdfit.read_table).");
  // fit(df, a_cols=..., b_cols=...): each selection, (spec, option), in a table with these column
  // labels, by the rules of a file's header (io::select_columns): 1-based positions.
  m.def(
      "select_columns",
      [](const std::vector<std::pair<std::string, std::string>>& selections, const std::vector<std::string>& names,
         const std::string& source) {
        std::vector<io::ColumnSelection> chosen;
        for (const auto& [spec, option] : selections) chosen.push_back({spec, option});
        return io::select_columns(chosen, names, source);
      },
      py::arg("selections"), py::arg("names"), py::arg("source"));
  m.def("describe_columns", &io::describe_columns, py::arg("positions"), py::arg("names"),
        "'columns acc1..acc6 (2-7)': 1-based positions and the names of the columns a selection chose.");
  m.def(
      "write_csv", [](const std::string& path, const Eigen::MatrixXd& X) { io::write_csv(path, X); },
      py::arg("path"), py::arg("X"), "Write X as CSV with values that read back exactly.");
}

}  // namespace spdfit::python
