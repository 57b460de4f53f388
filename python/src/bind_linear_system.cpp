// spdfit.solve: classify and solve A x = b (lecture notes 002, sections 3.3.2, 3.7-3.8).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "spdfit/linear_system.hpp"

namespace py = pybind11;

namespace spdfit::python {

void bind_linear_system(py::module_& m) {
  py::class_<ColumnClassification>(m, "ColumnClassification", "The classification of one right-hand side.")
      .def_readonly("consistent", &ColumnClassification::consistent)
      .def_readonly("finite_solution_dimension", &ColumnClassification::finite_solution_dimension)
      .def_readonly("at_infinity_dimension", &ColumnClassification::at_infinity_dimension)
      .def_readonly("augmented_rank", &ColumnClassification::augmented_rank)
      .def_readonly("residual_norm", &ColumnClassification::residual_norm)
      .def_readonly("backward_error", &ColumnClassification::backward_error);

  py::class_<LinearSystemResult>(m, "LinearSystemResult",
                                 "Rank, consistency, solution sets and the minimum-norm least-squares "
                                 "solution of A x = b, with an explanation in words.")
      .def_property_readonly("ok", &LinearSystemResult::ok)
      .def_readonly("message", &LinearSystemResult::message, "why it failed ('' on success)")
      .def_readonly("m", &LinearSystemResult::m)
      .def_readonly("n", &LinearSystemResult::n)
      .def_readonly("p", &LinearSystemResult::p, "number of right-hand sides")
      .def_property_readonly("shape", [](const LinearSystemResult& r) { return std::string(to_string(r.shape)); })
      .def_readonly("singular_values", &LinearSystemResult::singular_values)
      .def_readonly("threshold", &LinearSystemResult::threshold)
      .def_readonly("rank", &LinearSystemResult::rank)
      .def_readonly("nullity", &LinearSystemResult::nullity)
      .def_readonly("condition_number", &LinearSystemResult::condition_number)
      .def_readonly("reciprocal_condition_number", &LinearSystemResult::reciprocal_condition_number)
      .def_readonly("effective_condition_number", &LinearSystemResult::effective_condition_number)
      .def_readonly("consistent", &LinearSystemResult::consistent)
      .def_readonly("finite_solution_dimension", &LinearSystemResult::finite_solution_dimension)
      .def_readonly("at_infinity_dimension", &LinearSystemResult::at_infinity_dimension)
      .def_readonly("columns", &LinearSystemResult::columns)
      .def_readonly("solution", &LinearSystemResult::solution, "n x p minimum-norm least-squares solution")
      .def_readonly("residual_norm", &LinearSystemResult::residual_norm)
      .def_readonly("null_space", &LinearSystemResult::null_space, "orthonormal columns")
      .def_readonly("range", &LinearSystemResult::range, "orthonormal columns")
      .def_readonly("explanation", &LinearSystemResult::explanation)
      .def_readonly("warnings", &LinearSystemResult::warnings)
      .def("__repr__", [](const LinearSystemResult& r) {
        std::ostringstream out;
        out << "LinearSystemResult(rank=" << r.rank << ", nullity=" << r.nullity
            << ", consistent=" << (r.consistent ? "True" : "False")
            << ", finite_solution_dimension=" << r.finite_solution_dimension
            << ", at_infinity_dimension=" << r.at_infinity_dimension << ")\n"
            << r.explanation;
        return out.str();
      });

  m.def(
      "solve",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, std::optional<double> threshold) {
        LinearSystemOptions options;
        if (threshold) options.threshold = *threshold;
        std::string error;
        if (!options.is_valid(&error)) throw std::invalid_argument(error);
        py::gil_scoped_release release;
        return solve(A, B, options);
      },
      py::arg("A"), py::arg("b"), py::arg("threshold") = py::none());
}

}  // namespace spdfit::python
