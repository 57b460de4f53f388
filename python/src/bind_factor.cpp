// The triangular factor of [A B] as a Python value: made from data or from a file
// pair, merged, estimated from, and sent between processes as the library's own validated bytes
// (TriangularFactor::serialize), which are also its pickle. python/spdfit/factor.py is the public
// face (spdfit.Factor): it checks the arguments' types, warns and raises NumericalError.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <string_view>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/stream.hpp"
#include "spdfit/triangular_factor.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

py::bytes to_bytes(const TriangularFactor& factor) {
  std::string bytes;
  {
    py::gil_scoped_release release;
    bytes = factor.serialize();
  }
  return py::bytes(bytes);
}

// Throws std::invalid_argument (a ValueError) with deserialize's message for bytes that are not a
// factor.
TriangularFactor from_bytes(const py::bytes& bytes) {
  const std::string_view view = bytes;
  py::gil_scoped_release release;
  return TriangularFactor::deserialize(view);
}

}  // namespace

void bind_factor(py::module_& m) {
  py::class_<TriangularFactor>(
      m, "TriangularFactor",
      "The triangular factor R of the Householder QR of [A B] (spdfit.Factor wraps it).")
      .def(py::init<Eigen::Index, Eigen::Index>(), py::arg("n"), py::arg("d"),
           "The factor of no rows yet, for A with n columns and B with d.")
      .def_static(
          "from_data",
          [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
            return TriangularFactor::from_data(A, B);
          },
          py::arg("A"), py::arg("B"), py::call_guard<py::gil_scoped_release>(),
          "The factor of the data A and B.")
      .def_static("merged", &TriangularFactor::merged, py::arg("a"), py::arg("b"),
                  py::call_guard<py::gil_scoped_release>(),
                  "The factor of the union of both row sets; a and b are left unchanged.")
      .def("serialize", &to_bytes, "The factor's whole state as the library's bytes.")
      .def_static("deserialize", &from_bytes, py::arg("bytes"),
                  "The factor serialize wrote; ValueError otherwise.")
      .def_property_readonly("n", &TriangularFactor::n, "A's columns: X has n rows")
      .def_property_readonly("d", &TriangularFactor::d, "B's columns: X has d columns")
      .def_property_readonly("rows", &TriangularFactor::rows, "the rows accumulated")
      // The state is the serialized bytes, checked again when unpickled: the one serialization,
      // so that no front-end depends on the factor's internals (pickle.hpp's field tuples are for
      // the results, whose fields are public).
      .def(py::pickle(&to_bytes, &from_bytes));

  // fit(reduce(factor, options), method): the estimate of the streaming fit, which for a factor
  // of all the rows is spdfit.fit's. No bootstrap: a factor has no rows to resample.
  m.def(
      "fit_factor",
      [](const TriangularFactor& factor, const py::handle& method, const py::dict& options) {
        std::vector<std::string_view> given;
        FitRequest base;
        base.method = method_from(method);
        const FitRequest request = fit_request("Factor.fit", options, base, given);
        check_fit_request(request, given);
        py::gil_scoped_release release;
        return fit(reduce(factor, request.options), request.method);
      },
      py::arg("factor"), py::arg("method"), py::arg("options"));

  // (factor, the readers' warnings) of a file pair read a block of rows at a time.
  m.def(
      "stream_factor",
      [](const std::string& a_path, const std::string& b_path, Eigen::Index block_rows, unsigned threads) {
        StreamOptions options;
        options.block_rows = block_rows;
        options.threads = threads;
        std::vector<Warning> warnings;
        TriangularFactor factor = [&] {
          py::gil_scoped_release release;
          return stream_factor(a_path, b_path, options, &warnings);
        }();
        return py::make_tuple(std::move(factor), warnings);
      },
      py::arg("A_path"), py::arg("B_path"), py::arg("block_rows") = StreamOptions{}.block_rows,
      py::arg("threads") = StreamOptions{}.threads);
}

}  // namespace spdfit::python
