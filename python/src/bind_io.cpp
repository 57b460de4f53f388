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
  m.def(
      "write_csv", [](const std::string& path, const Eigen::MatrixXd& X) { io::write_csv(path, X); },
      py::arg("path"), py::arg("X"), "Write X as CSV with values that read back exactly.");
}

}  // namespace spdfit::python
