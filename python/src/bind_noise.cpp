// spdfit.NoiseModel: the covariances of the noise in A and B, which fit, fit_files, Factor.fit and
// hexapod.identify take as noise=. Made by its constructor (covariances), from_std or from_rest;
// pickled and shown through the library's JSON.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>

#include "bindings.hpp"
#include "pickle.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/options.hpp"
#include "spdfit/render.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// The library names its options (`noise_cov_a`, `noise_std_b`, `rest_a`); NoiseModel's own
// arguments are cov_a, std_b, rest_a: a ValueError in their spelling.
template <typename Make>
NoiseModel made(Make&& make) {
  try {
    return std::forward<Make>(make)();
  } catch (const OptionError& e) {
    std::string message = e.what();
    for (const auto& [library, python] : {std::pair<std::string, std::string>{"`noise_cov_a`", "cov_a"},
                                          {"`noise_cov_b`", "cov_b"},
                                          {"`noise_std_a`", "std_a"},
                                          {"`noise_std_b`", "std_b"},
                                          {"`rest_a`", "rest_a"},
                                          {"`rest_b`", "rest_b"},
                                          {"`block_rows`", "block_rows"}}) {
      for (std::size_t at = message.find(library); at != std::string::npos; at = message.find(library, at)) {
        message.replace(at, library.size(), python);
      }
    }
    throw py::value_error(message);
  }
}

// One standard deviation (a number) or one per column (a sequence), as a vector.
Eigen::VectorXd deviations(const py::handle& value, const char* name) {
  if (py::isinstance<py::bool_>(value)) throw py::type_error(std::string(name) + " must be a number or a sequence of numbers, got bool");
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
      py::isinstance(value, py::module_::import("numbers").attr("Real"))) {
    return Eigen::VectorXd::Constant(1, py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>());
  }
  py::array array = py::module_::import("numpy").attr("asarray")(value, "float64");
  if (array.ndim() > 1) throw py::value_error(std::string(name) + " must be a number or a vector, got " + std::to_string(array.ndim()) + " dimensions");
  return py::cast<Eigen::VectorXd>(array.attr("reshape")(-1));
}

}  // namespace

void bind_noise(py::module_& m) {
  py::class_<NoiseModel>(
      m, "NoiseModel",
      "The noise in A and B: Sigma_A (n x n) and Sigma_B (d x d), the covariances of the noise in each row\n"
      "of A and of B, the same for every row, independent between rows and between A and B.\n\n"
      "NoiseModel(cov_a=..., cov_b=...) takes the covariances (symmetric positive semidefinite);\n"
      "NoiseModel.from_std(std_a, std_b) standard deviations, one per side or one per column (0: exact);\n"
      "NoiseModel.from_rest(rest_a, rest_b) rows recorded with the machine at rest (their sample\n"
      "covariances, about their own means, so that a constant load is not noise). fit, fit_files,\n"
      "Factor.fit and hexapod.identify take it as noise=: spd-tls and auto become the maximum-likelihood\n"
      "fit, psd-ls and procrustes weighted by B's noise, the tls methods generalized TLS; spde takes none.\n"
      "Bad input is a ValueError naming the argument.")
      .def(py::init([](const Eigen::MatrixXd& cov_a, const Eigen::MatrixXd& cov_b) {
             return made([&] { return NoiseModel::from_cov(cov_a, cov_b); });
           }),
           py::kw_only(), py::arg("cov_a"), py::arg("cov_b"),
           "The covariances Sigma_A (n x n) and Sigma_B (d x d): symmetric (to 1e-10 of the largest entry; the "
           "symmetric part is kept) and positive semidefinite.")
      .def_static(
          "from_std",
          [](const py::object& std_a, const py::object& std_b) {
            const Eigen::VectorXd a = deviations(std_a, "std_a");
            const Eigen::VectorXd b = deviations(std_b, "std_b");
            return made([&] { return NoiseModel::from_std(a, b); });
          },
          py::arg("std_a"), py::arg("std_b"),
          "Standard deviations of the noise in A and in B, in the data's units: a number for every column of "
          "that side, or one per column; 0 means exact. Sigma = diag(std^2).")
      .def_static(
          "from_rest",
          [](const Eigen::MatrixXd& rest_a, const Eigen::MatrixXd& rest_b) {
            return made([&] { return NoiseModel::from_rest(rest_a, rest_b); });
          },
          py::arg("rest_a"), py::arg("rest_b"),
          "The sample covariances (divisor N - 1, about each side's own mean) of N rows of A and N rows of B "
          "recorded with the machine at rest (accelerations zero, forces constant). warnings says when there are "
          "fewer than 10 rows per column, or when A's rest rows' mean is far from zero (perhaps not at rest).")
      .def_static(
          "from_rest_files",
          [](const std::string& rest_a, const std::string& rest_b) {
            return made([&] { return NoiseModel::from_rest_files(rest_a, rest_b); });
          },
          py::arg("rest_a"), py::arg("rest_b"),
          "from_rest with the rows in files (any format fit_files reads), streamed: memory does not grow with "
          "their length. DataError naming the file for bad data.")
      .def_property_readonly("source", [](const NoiseModel& model) { return std::string(to_string(model.source())); },
                             "'std', 'cov' or 'rest'")
      .def_property_readonly(
          "cov_a",
          [](const NoiseModel& model) -> std::optional<Eigen::MatrixXd> {
            if (model.cov_a().size() == 0) return std::nullopt;
            return model.cov_a();
          },
          "Sigma_A (None for one standard deviation per side: its size comes from the data)")
      .def_property_readonly(
          "cov_b",
          [](const NoiseModel& model) -> std::optional<Eigen::MatrixXd> {
            if (model.cov_b().size() == 0) return std::nullopt;
            return model.cov_b();
          },
          "Sigma_B (None as cov_a)")
      .def_property_readonly(
          "std_a",
          [](const NoiseModel& model) -> std::optional<Eigen::VectorXd> {
            if (model.std_a().size() == 0) return std::nullopt;
            return model.std_a();
          },
          "the standard deviations as given (source 'std'; else None)")
      .def_property_readonly(
          "std_b",
          [](const NoiseModel& model) -> std::optional<Eigen::VectorXd> {
            if (model.std_b().size() == 0) return std::nullopt;
            return model.std_b();
          },
          "as std_a, for B")
      .def_property_readonly("rest_rows", &NoiseModel::rest_rows, "the number of rest rows (source 'rest'; else None)")
      .def_property_readonly("warnings", [](const NoiseModel& model) { return texts(model.warnings()); },
                             "what from_rest found for the user to know")
      .def_property_readonly("warning_codes", [](const NoiseModel& model) {
        std::vector<std::string> out;
        for (const Warning& w : model.warnings()) out.emplace_back(code_info(w.code).name);
        return out;
      }, "each warning's code (spdfit.outcome_codes())")
      .def(pickle_json<NoiseModel>("NoiseModel",
                                   [](const NoiseModel& model, JsonStyle style) { return to_json(model, style); }))
      .def("__repr__", [](const NoiseModel& model) { return repr_from_json("NoiseModel", to_json(model)); });
}

}  // namespace spdfit::python
