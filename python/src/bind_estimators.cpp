// The estimators and their results. The functions here never raise for a numerical failure:
// they return the FitResult; python/spdfit/__init__.py raises NumericalError and warns.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "bindings.hpp"
#include "spdfit/area_criterion.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/nearest_spd.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

Method method_from(const std::string& name) {
  if (const auto method = parse_method(name)) return *method;
  std::string known;
  for (Method m : kSelectableMethods) known += (known.empty() ? "" : ", ") + std::string(to_string(m));
  throw std::invalid_argument("unknown method '" + name + "' (methods: " + known + ")");
}

// The options of a Python call; noise_ratio is refused (ValueError) for a method that does not
// take it, as the CLI refuses --noise-ratio.
FitOptions options_from(const std::optional<double>& rank_tolerance, const std::optional<double>& noise_ratio = {},
                        std::optional<Method> method = {}) {
  FitOptions options;
  if (rank_tolerance) options.rank_tolerance = *rank_tolerance;
  if (noise_ratio) {
    if (method && !uses_noise_ratio(*method)) {
      throw std::invalid_argument("noise_ratio applies to the total least-squares methods (tls, tls-sym, "
                                  "tls-psd), not to " +
                                  std::string(to_string(*method)));
    }
    options.noise_ratio = *noise_ratio;
  }
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  return options;
}

std::string repr(const FitResult& r) {
  std::ostringstream out;
  out << "FitResult(method='" << to_string(r.method) << "', ";
  if (!r.ok()) {
    out << "failed: " << r.message << ")";
    return out.str();
  }
  const Diagnostics& d = r.diagnostics;
  out << "n=" << d.n << ", m=" << d.m << ", residual_norm=" << d.residual_norm;
  if (d.symmetric) out << ", positive_definite=" << (d.positive_definite ? "True" : "False");
  if (d.area_criterion) out << ", area_criterion=" << *d.area_criterion;
  if (!r.warnings.empty()) out << ", warnings=" << r.warnings.size();
  out << ")\nX =\n" << r.X;
  return out.str();
}

}  // namespace

void bind_estimators(py::module_& m) {
  py::class_<Diagnostics>(m, "Diagnostics",
                          "What an estimate is checked by: ranks and condition numbers of A and B, the "
                          "residual, definiteness, the area criterion and method-specific values "
                          "(None where not defined).")
      .def_readonly("m", &Diagnostics::m, "rows (samples)")
      .def_readonly("n", &Diagnostics::n, "columns; X is n x n")
      .def_readonly("rank_a", &Diagnostics::rank_a)
      .def_readonly("rank_b", &Diagnostics::rank_b)
      .def_readonly("cond_a", &Diagnostics::cond_a, "sigma_max / sigma_min of A (inf when singular)")
      .def_readonly("cond_b", &Diagnostics::cond_b)
      .def_readonly("singular_values_a", &Diagnostics::singular_values_a)
      .def_readonly("singular_values_b", &Diagnostics::singular_values_b)
      .def_readonly("residual_norm", &Diagnostics::residual_norm, "||A X - B||_F")
      .def_readonly("symmetric", &Diagnostics::symmetric)
      .def_readonly("positive_definite", &Diagnostics::positive_definite)
      .def_readonly("positive_semidefinite", &Diagnostics::positive_semidefinite)
      .def_readonly("min_eigenvalue", &Diagnostics::min_eigenvalue)
      .def_readonly("max_eigenvalue", &Diagnostics::max_eigenvalue)
      .def_readonly("area_criterion", &Diagnostics::area_criterion,
                    "||A Y - B Y^-T||_F^2 with X = Y Y^T (Chen & McInroy, Definition II.1)")
      .def_readonly("area_criterion_minimum", &Diagnostics::area_criterion_minimum,
                    "spde: 2 tr(Sigma_Q~ - A^T B) (Corollary III.4)")
      .def_readonly("cross_term_positive_definite", &Diagnostics::cross_term_positive_definite,
                    "procrustes: A^T B + B^T A positive definite (thesis Theorem 3.2 (3))")
      .def_readonly("tls_sigma_n", &Diagnostics::tls_sigma_n)
      .def_readonly("tls_sigma_n1", &Diagnostics::tls_sigma_n1)
      .def_readonly("tls_correction_norm", &Diagnostics::tls_correction_norm, "thesis eq. 4.33")
      .def_readonly("tls_v22_min_singular_value", &Diagnostics::tls_v22_min_singular_value)
      .def_readonly("noise_sigma", &Diagnostics::noise_sigma,
                    "noise standard deviation in A under the TLS model (noise_ratio times it in B); "
                    "None when m == n")
      .def("__repr__", [](const Diagnostics& d) {
        std::ostringstream out;
        out << "Diagnostics(m=" << d.m << ", n=" << d.n << ", rank_a=" << d.rank_a << ", rank_b=" << d.rank_b
            << ", cond_a=" << d.cond_a << ", cond_b=" << d.cond_b << ", residual_norm=" << d.residual_norm
            << ")";
        return out.str();
      });

  py::class_<FitResult>(m, "FitResult", "An estimate of X in A X ~= B with its diagnostics and warnings.")
      .def_property_readonly("method", [](const FitResult& r) { return std::string(to_string(r.method)); })
      .def_property_readonly("ok", &FitResult::ok)
      .def_property_readonly("status", [](const FitResult& r) { return std::string(to_string(r.status)); },
                             "'success', 'numerical_failure', or 'not_computed' (no estimator filled it)")
      .def_readonly("message", &FitResult::message, "why it failed ('' on success)")
      .def_readonly("X", &FitResult::X, "the estimate (n x n ndarray; empty on failure)")
      .def_readonly("diagnostics", &FitResult::diagnostics)
      .def_readonly("warnings", &FitResult::warnings)
      .def("__repr__", &repr);

  m.def(
      "fit",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const std::string& method,
         std::optional<double> rank_tolerance, std::optional<double> noise_ratio) {
        const Method chosen = method_from(method);
        const FitOptions options = options_from(rank_tolerance, noise_ratio, chosen);
        py::gil_scoped_release release;
        return fit(A, B, chosen, options);
      },
      py::arg("A"), py::arg("B"), py::arg("method"), py::arg("rank_tolerance") = py::none(),
      py::arg("noise_ratio") = py::none());
  py::class_<StreamOptions>(m, "StreamOptions",
                            "How fit_files streams its files; the defaults are the library's own.")
      .def(py::init<>())
      .def_readwrite("block_rows", &StreamOptions::block_rows, "rows per block")
      .def_readwrite("threads", &StreamOptions::threads, "threads; 0 means one per core");
  m.def(
      "fit_files",
      [](const std::string& a_path, const std::string& b_path, const std::string& method, Eigen::Index block_rows,
         unsigned threads, std::optional<double> rank_tolerance, std::optional<double> noise_ratio) {
        const Method chosen = method_from(method);
        const FitOptions options = options_from(rank_tolerance, noise_ratio, chosen);
        StreamOptions stream;
        stream.block_rows = block_rows;
        stream.threads = threads;
        py::gil_scoped_release release;
        return fit_files(a_path, b_path, chosen, options, stream);
      },
      py::arg("A_path"), py::arg("B_path"), py::arg("method"), py::arg("block_rows") = StreamOptions{}.block_rows,
      py::arg("threads") = StreamOptions{}.threads, py::arg("rank_tolerance") = py::none(),
      py::arg("noise_ratio") = py::none());
  m.def(
      "fit_all",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, std::optional<double> rank_tolerance,
         std::optional<double> noise_ratio) {
        const FitOptions options = options_from(rank_tolerance, noise_ratio);
        py::gil_scoped_release release;
        return fit_all(A, B, options);
      },
      py::arg("A"), py::arg("B"), py::arg("rank_tolerance") = py::none(), py::arg("noise_ratio") = py::none());

  py::class_<NearestSpdResult>(m, "NearestSpdResult", "The nearest matrix and how far it moved.")
      .def_readonly("X", &NearestSpdResult::X)
      .def_readonly("distance", &NearestSpdResult::distance, "||X_in - X||_F")
      .def_readonly("clipped", &NearestSpdResult::clipped, "eigenvalues raised to min_eig")
      .def_readonly("min_eigenvalue_before", &NearestSpdResult::min_eigenvalue_before)
      .def("__repr__", [](const NearestSpdResult& r) {
        std::ostringstream out;
        out << "NearestSpdResult(distance=" << r.distance << ", clipped=" << r.clipped << ")\nX =\n" << r.X;
        return out.str();
      });
  m.def("nearest_spd", &nearest_spd, py::arg("X"), py::arg("min_eig") = 0.0,
        py::call_guard<py::gil_scoped_release>());

  m.def(
      "area_criterion",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& X) {
        return area_criterion(A, B, X);
      },
      py::arg("A"), py::arg("B"), py::arg("X"), py::call_guard<py::gil_scoped_release>());
}

}  // namespace spdfit::python
