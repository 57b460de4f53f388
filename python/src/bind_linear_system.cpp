// spdfit.solve: classify and solve A x = b (lecture notes 002, sections 3.3.2, 3.7-3.8).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/render.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// The Python class LinearSystemResult: the library's result and whether b was 1-D, so that
// `solution` has b's dimensionality, as numpy.linalg.lstsq's x has: shape (n,) for b of shape
// (m,), (n, p) for (m, p). The library itself takes and returns matrices (B m x p, X n x p).
struct SolveResult : LinearSystemResult {
  bool vector_b = false;
};

// The getter of a field of the library's result: a copy, as copied() (bindings.hpp) gives.
template <typename Member>
auto result_field(Member LinearSystemResult::*member) {
  return [member](const SolveResult& r) -> Member { return r.*member; };
}

// The state's payload: the library's exact JSON of the result, and whether b was 1-D.
py::tuple solve_payload(const SolveResult& r) {
  return py::make_tuple(to_json(static_cast<const LinearSystemResult&>(r), JsonStyle::Exact), r.vector_b);
}

SolveResult solve_result_from(const py::tuple& state) {
  const char* what = "LinearSystemResult";
  const auto payload = checked_payload(state, what).cast<py::tuple>();
  check_state(payload, 2, what);
  return SolveResult{object_from_json<LinearSystemResult>(py::object(payload[0]), what), payload[1].cast<bool>()};
}

}  // namespace

void bind_linear_system(py::module_& m) {
  py::class_<ColumnClassification>(m, "ColumnClassification", "The classification of one right-hand side.")
      .def_property_readonly("consistent", copied(&ColumnClassification::consistent))
      .def_property_readonly("finite_solution_dimension", copied(&ColumnClassification::finite_solution_dimension))
      .def_property_readonly("at_infinity_dimension", copied(&ColumnClassification::at_infinity_dimension))
      .def_property_readonly("augmented_rank", copied(&ColumnClassification::augmented_rank))
      .def_property_readonly("residual_norm", copied(&ColumnClassification::residual_norm))
      .def_property_readonly("backward_error", copied(&ColumnClassification::backward_error))
      .def(pickle_json<ColumnClassification>(
          "ColumnClassification", [](const ColumnClassification& c, JsonStyle style) { return to_json(c, style); }))
      .def("__repr__",
           [](const ColumnClassification& c) { return repr_from_json("ColumnClassification", to_json(c)); });

  py::class_<SolveResult>(m, "LinearSystemResult",
                          "Rank, consistency, solution sets and the minimum-norm least-squares "
                          "solution of A x = b, with an explanation in words.")
      .def_property_readonly("ok", [](const SolveResult& r) { return r.ok(); })
      .def_property_readonly("message", result_field(&LinearSystemResult::message), "why it failed ('' on success)")
      .def_property_readonly("m", result_field(&LinearSystemResult::m))
      .def_property_readonly("n", result_field(&LinearSystemResult::n))
      .def_property_readonly("p", result_field(&LinearSystemResult::p), "number of right-hand sides (1 for a 1-D b)")
      .def_property_readonly("shape", [](const SolveResult& r) { return std::string(to_string(r.shape)); })
      .def_property_readonly("singular_values", result_field(&LinearSystemResult::singular_values))
      .def_property_readonly("threshold", result_field(&LinearSystemResult::rank_tolerance))
      .def_property_readonly("rank", result_field(&LinearSystemResult::rank))
      .def_property_readonly("nullity", result_field(&LinearSystemResult::nullity))
      .def_property_readonly("condition_number", result_field(&LinearSystemResult::condition_number))
      .def_property_readonly("reciprocal_condition_number",
                             result_field(&LinearSystemResult::reciprocal_condition_number))
      .def_property_readonly("effective_condition_number",
                             result_field(&LinearSystemResult::effective_condition_number))
      .def_property_readonly("scaled_singular_values", result_field(&LinearSystemResult::scaled_singular_values))
      .def_property_readonly("scaled_condition_number", result_field(&LinearSystemResult::scaled_condition_number))
      .def_property_readonly("refinement_steps", result_field(&LinearSystemResult::refinement_steps))
      .def_property_readonly("consistent", result_field(&LinearSystemResult::consistent))
      .def_property_readonly("finite_solution_dimension", result_field(&LinearSystemResult::finite_solution_dimension))
      .def_property_readonly("at_infinity_dimension", result_field(&LinearSystemResult::at_infinity_dimension))
      .def_property_readonly("columns", result_field(&LinearSystemResult::columns),
                             "one ColumnClassification per right-hand side (a list of one for a 1-D b)")
      .def_property_readonly(
          "solution",
          [](const SolveResult& r) -> py::object {
            // reshaped, not col(0): a failed result's solution is empty.
            if (r.vector_b) return py::cast(Eigen::VectorXd(r.solution.reshaped()));
            return py::cast(Eigen::MatrixXd(r.solution));
          },
          "the minimum-norm least-squares solution: shape (n,) for a 1-D b, (n, p) for an m x p b; "
          "empty on failure")
      .def_property_readonly("residual_norm", result_field(&LinearSystemResult::residual_norm),
                             "||A X - B||_F (||A x - b||_2 for a 1-D b)")
      .def_property_readonly("null_space", result_field(&LinearSystemResult::null_space), "orthonormal columns")
      .def_property_readonly("range", result_field(&LinearSystemResult::range), "orthonormal columns")
      .def_property_readonly("explanation", result_field(&LinearSystemResult::explanation))
      .def_property_readonly("warnings", [](const SolveResult& r) { return texts(r.warnings); })
      .def_property_readonly("warning_codes", [](const SolveResult& r) {
        std::vector<std::string> out;
        for (const Warning& w : r.warnings) out.emplace_back(code_info(w.code).name);
        return out;
      }, "each warning's code (spdfit.outcome_codes())")
      .def(py::pickle([](const SolveResult& r) { return py::make_tuple(kPickleFormat, solve_payload(r)); },
                      &solve_result_from))
      .def("__repr__", [](const SolveResult& r) {
        std::ostringstream out;
        out << "LinearSystemResult(rank=" << r.rank << ", nullity=" << r.nullity
            << ", consistent=" << (r.consistent ? "True" : "False")
            << ", finite_solution_dimension=" << r.finite_solution_dimension
            << ", at_infinity_dimension=" << r.at_infinity_dimension << ")\n"
            << report(r);
        return out.str();
      });

  m.def(
      "solve",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, std::optional<double> threshold, bool vector_b) {
        LinearSystemOptions options;
        options.rank_tolerance = threshold;
        std::string error;
        if (!options.is_valid(&error)) throw std::invalid_argument(error);
        if (vector_b && B.cols() != 1) throw std::invalid_argument("vector_b=True needs b with one column");
        py::gil_scoped_release release;
        return SolveResult{solve(A, B, options), vector_b};
      },
      py::arg("A"), py::arg("b"), py::arg("threshold") = py::none(), py::arg("vector_b") = false,
      "solve(A, B) as a LinearSystemResult; vector_b: b was 1-D (B is its column), so the solution is 1-D.");
}

}  // namespace spdfit::python
