// Reading and writing data files from Python, with DataError as a ValueError subclass.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "spdfit/io.hpp"

namespace py = pybind11;

namespace spdfit::python {

void bind_io(py::module_& m) {
  static py::exception<io::DataError> data_error(m, "DataError", PyExc_ValueError);
  data_error.doc() = "Bad input data; the message names the file and, for text, the line and column.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::DataError& e) {
      data_error(e.what());
    }
  });

  m.def(
      "read_matrix", [](const std::string& path, bool allow_nonfinite) {
        io::ReadOptions options;
        options.allow_nonfinite = allow_nonfinite;
        return io::read_matrix(path, options);
      },
      py::arg("path"), py::kw_only(), py::arg("allow_nonfinite") = false,
      py::call_guard<py::gil_scoped_release>(),
      "Read a matrix from delimited text (commas, semicolons, tabs or spaces; '#' comments; an "
      "optional header row) or a .npy file (float64). Raises DataError (a ValueError) naming the "
      "file, line and column on bad input; NaN and Inf are rejected unless allow_nonfinite.");
  m.def(
      "read_table", [](const std::string& path) {
        io::Table table = io::read_table(path);
        return py::make_tuple(table.values, table.column_names);
      },
      py::arg("path"), "Like read_matrix, but returns (values, column_names from the header row).");
  m.def(
      "write_csv", [](const std::string& path, const Eigen::MatrixXd& X) { io::write_csv(path, X); },
      py::arg("path"), py::arg("X"), "Write X as CSV with values that read back exactly.");
}

}  // namespace spdfit::python
