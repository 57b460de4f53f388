// spdfit.linkage: four-bar function-generator synthesis and analysis (notes 002, 3.3-3.6).
// Angles are radians here; python/spdfit/linkage.py offers degrees.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/grashof.hpp"
#include "spdfit/linkage/prescribed_function.hpp"
#include "spdfit/linkage/status.hpp"
#include "spdfit/linkage/synthesis.hpp"

namespace py = pybind11;

namespace spdfit::python {

using namespace spdfit::linkage;

void bind_linkage(py::module_& parent) {
  py::module_ m = parent.def_submodule("linkage", "Four-bar synthesis and analysis (radians).");

  py::class_<FourBar>(m, "FourBar", "Link lengths: a1 ground, a2 input, a3 coupler, a4 output.")
      .def(py::init([](double a1, double a2, double a3, double a4) { return FourBar{a1, a2, a3, a4}; }),
           py::arg("a1"), py::arg("a2"), py::arg("a3"), py::arg("a4"))
      .def_property_readonly("a1", copied(&FourBar::a1))
      .def_property_readonly("a2", copied(&FourBar::a2))
      .def_property_readonly("a3", copied(&FourBar::a3))
      .def_property_readonly("a4", copied(&FourBar::a4))
      .def("__repr__", [](const FourBar& b) {
        std::ostringstream out;
        out << "FourBar(a1=" << b.a1 << ", a2=" << b.a2 << ", a3=" << b.a3 << ", a4=" << b.a4 << ")";
        return out.str();
      });

  py::class_<AngleRange>(m, "AngleRange").def_property_readonly("min", copied(&AngleRange::min)).def_property_readonly("max", copied(&AngleRange::max));
  py::class_<DialZeros>(m, "DialZeros").def_property_readonly("alpha", copied(&DialZeros::alpha)).def_property_readonly("beta", copied(&DialZeros::beta));

  py::class_<MotionCheck>(m, "MotionCheck")
      .def_property_readonly("grashof", [](const MotionCheck& c) { return std::string(to_string(c.grashof)); })
      .def_property_readonly("transmission", copied(&MotionCheck::transmission))
      .def_property_readonly("dead_points", copied(&MotionCheck::dead_points))
      .def_property_readonly("branch_defect", copied(&MotionCheck::branch_defect))
      .def_property_readonly("branch_defect_reason", copied(&MotionCheck::branch_defect_reason));

  py::class_<LinkageSolution>(m, "LinkageSolution")
      .def_property_readonly("k", copied(&LinkageSolution::k))
      .def_property_readonly("dial_zeros", copied(&LinkageSolution::dial_zeros))
      .def_property_readonly("lengths", copied(&LinkageSolution::lengths))
      .def_property_readonly("no_linkage_reason", copied(&LinkageSolution::no_linkage_reason))
      .def_property_readonly("design_error_norm", copied(&LinkageSolution::design_error_norm))
      .def_property_readonly("structural_error_rms", copied(&LinkageSolution::structural_error_rms))
      .def_property_readonly("structural_error_max", copied(&LinkageSolution::structural_error_max))
      .def_property_readonly("phi_generated", copied(&LinkageSolution::phi_generated))
      .def_property_readonly("iterations", copied(&LinkageSolution::iterations))
      .def_property_readonly("final_step_norm", copied(&LinkageSolution::final_step_norm))
      .def_property_readonly("check", copied(&LinkageSolution::check));

  py::class_<SynthesisResult>(m, "SynthesisResult")
      .def_property_readonly("ok", &SynthesisResult::ok)
      .def_property_readonly("status", [](const SynthesisResult& r) { return std::string(to_string(r.status)); })
      .def_property_readonly("message", copied(&SynthesisResult::message))
      .def_property_readonly("positions", copied(&SynthesisResult::positions))
      .def_property_readonly("precision_point", copied(&SynthesisResult::precision_point))
      .def_property_readonly("dial_zeros_fitted", copied(&SynthesisResult::dial_zeros_fitted))
      .def_property_readonly("branch", copied(&SynthesisResult::branch))
      .def_property_readonly("rank", copied(&SynthesisResult::rank))
      .def_property_readonly("condition_number", copied(&SynthesisResult::condition_number))
      .def_property_readonly("scaled_condition_number", copied(&SynthesisResult::scaled_condition_number))
      .def_property_readonly("used_svd", copied(&SynthesisResult::used_svd))
      .def_property_readonly("psi", copied(&SynthesisResult::psi))
      .def_property_readonly("phi", copied(&SynthesisResult::phi))
      .def_property_readonly("design", copied(&SynthesisResult::design))
      .def_property_readonly("structural", copied(&SynthesisResult::structural))
      .def_property_readonly("warnings", copied(&SynthesisResult::warnings));

  py::class_<GaussNewtonOptions>(m, "GaussNewtonOptions",
                                 "Gauss-Newton on the structural error; the defaults are the library's.")
      .def(py::init<>())
      .def_readwrite("tolerance", &GaussNewtonOptions::tolerance)
      .def_readwrite("max_iterations", &GaussNewtonOptions::max_iterations);

  m.def(
      "synthesize",
      [](const Eigen::VectorXd& delta_psi, const Eigen::VectorXd& delta_phi, const Eigen::VectorXd& weights,
         std::optional<double> alpha, std::optional<double> beta, bool fit_dial_zeros, bool refine,
         double tolerance, int max_iterations) {
        SynthesisOptions options;
        options.alpha = alpha;
        options.beta = beta;
        options.fit_dial_zeros = fit_dial_zeros;
        options.refine = refine;
        options.gauss_newton.tolerance = tolerance;
        options.gauss_newton.max_iterations = max_iterations;
        std::string error;
        if (!options.is_valid(&error)) throw std::invalid_argument(error);
        py::gil_scoped_release release;
        return synthesize(delta_psi, delta_phi, weights, options);
      },
      py::arg("delta_psi"), py::arg("delta_phi"), py::arg("weights"), py::arg("alpha"), py::arg("beta"),
      py::arg("fit_dial_zeros"), py::arg("refine"), py::arg("tolerance"), py::arg("max_iterations"));

  m.def("steering_pairs", [](double rho, double lo, double hi, int n, const std::string& spacing) {
    const PrescribedPairs p = steering_pairs(rho, lo, hi, n, spacing == "chebyshev" ? Spacing::Chebyshev : Spacing::Uniform);
    return py::make_tuple(p.delta_psi, p.delta_phi);
  });
  m.def("function_pairs", [](const std::string& name, double x_lo, double x_hi, double psi_lo, double psi_hi,
                             double phi_lo, double phi_hi, int n, const std::string& spacing) {
    const PrescribedPairs p = function_pairs(name, x_lo, x_hi, psi_lo, psi_hi, phi_lo, phi_hi, n,
                                             spacing == "chebyshev" ? Spacing::Chebyshev : Spacing::Uniform);
    return py::make_tuple(p.delta_psi, p.delta_phi);
  });
  m.def("function_names", &function_names);
  m.def("trapezoid_dial_zeros", &trapezoid_dial_zeros, py::arg("rho"));
  m.def("freudenstein_parameters", &freudenstein_parameters, py::arg("bar"));
  m.def(
      "link_lengths",
      [](const Eigen::Vector3d& k) {
        std::string problem;
        auto bar = link_lengths(k, &problem);
        if (!bar) throw std::invalid_argument(problem);
        return *bar;
      },
      py::arg("k"));
  m.def("grashof_type", [](const FourBar& bar) { return std::string(to_string(grashof_type(bar))); });

  py::class_<AnalysisSample>(m, "AnalysisSample")
      .def_property_readonly("psi", copied(&AnalysisSample::psi))
      .def_property_readonly("phi_plus", copied(&AnalysisSample::phi_plus))
      .def_property_readonly("phi_minus", copied(&AnalysisSample::phi_minus))
      .def_property_readonly("transmission_angle", copied(&AnalysisSample::transmission_angle));
  py::class_<Analysis>(m, "Analysis")
      .def_property_readonly("bar", copied(&Analysis::bar))
      .def_property_readonly("k", copied(&Analysis::k))
      .def_property_readonly("grashof", [](const Analysis& a) { return std::string(to_string(a.grashof)); })
      .def_property_readonly("input_fully_rotates", copied(&Analysis::input_fully_rotates))
      .def_property_readonly("dead_points", copied(&Analysis::dead_points))
      .def_property_readonly("samples", copied(&Analysis::samples))
      .def_property_readonly("transmission", copied(&Analysis::transmission));
  m.def("analyze", &analyze, py::arg("bar"), py::arg("psi"), py::call_guard<py::gil_scoped_release>());
}

}  // namespace spdfit::python
