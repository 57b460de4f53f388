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
      .def_readonly("a1", &FourBar::a1)
      .def_readonly("a2", &FourBar::a2)
      .def_readonly("a3", &FourBar::a3)
      .def_readonly("a4", &FourBar::a4)
      .def("__repr__", [](const FourBar& b) {
        std::ostringstream out;
        out << "FourBar(a1=" << b.a1 << ", a2=" << b.a2 << ", a3=" << b.a3 << ", a4=" << b.a4 << ")";
        return out.str();
      });

  py::class_<AngleRange>(m, "AngleRange").def_readonly("min", &AngleRange::min).def_readonly("max", &AngleRange::max);
  py::class_<DialZeros>(m, "DialZeros").def_readonly("alpha", &DialZeros::alpha).def_readonly("beta", &DialZeros::beta);

  py::class_<MotionCheck>(m, "MotionCheck")
      .def_property_readonly("grashof", [](const MotionCheck& c) { return std::string(to_string(c.grashof)); })
      .def_readonly("transmission", &MotionCheck::transmission)
      .def_readonly("dead_points", &MotionCheck::dead_points)
      .def_readonly("branch_defect", &MotionCheck::branch_defect)
      .def_readonly("branch_defect_reason", &MotionCheck::branch_defect_reason);

  py::class_<LinkageSolution>(m, "LinkageSolution")
      .def_readonly("k", &LinkageSolution::k)
      .def_readonly("dial_zeros", &LinkageSolution::dial_zeros)
      .def_readonly("lengths", &LinkageSolution::lengths)
      .def_readonly("no_linkage_reason", &LinkageSolution::no_linkage_reason)
      .def_readonly("design_error_norm", &LinkageSolution::design_error_norm)
      .def_readonly("structural_error_rms", &LinkageSolution::structural_error_rms)
      .def_readonly("structural_error_max", &LinkageSolution::structural_error_max)
      .def_readonly("phi_generated", &LinkageSolution::phi_generated)
      .def_readonly("iterations", &LinkageSolution::iterations)
      .def_readonly("final_step_norm", &LinkageSolution::final_step_norm)
      .def_readonly("check", &LinkageSolution::check);

  py::class_<SynthesisResult>(m, "SynthesisResult")
      .def_property_readonly("ok", &SynthesisResult::ok)
      .def_property_readonly("status", [](const SynthesisResult& r) { return std::string(to_string(r.status)); })
      .def_readonly("message", &SynthesisResult::message)
      .def_readonly("positions", &SynthesisResult::positions)
      .def_readonly("precision_point", &SynthesisResult::precision_point)
      .def_readonly("dial_zeros_fitted", &SynthesisResult::dial_zeros_fitted)
      .def_readonly("branch", &SynthesisResult::branch)
      .def_readonly("rank", &SynthesisResult::rank)
      .def_readonly("condition_number", &SynthesisResult::condition_number)
      .def_readonly("used_svd", &SynthesisResult::used_svd)
      .def_readonly("psi", &SynthesisResult::psi)
      .def_readonly("phi", &SynthesisResult::phi)
      .def_readonly("design", &SynthesisResult::design)
      .def_readonly("structural", &SynthesisResult::structural)
      .def_readonly("warnings", &SynthesisResult::warnings);

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
      .def_readonly("psi", &AnalysisSample::psi)
      .def_readonly("phi_plus", &AnalysisSample::phi_plus)
      .def_readonly("phi_minus", &AnalysisSample::phi_minus)
      .def_readonly("transmission_angle", &AnalysisSample::transmission_angle);
  py::class_<Analysis>(m, "Analysis")
      .def_readonly("bar", &Analysis::bar)
      .def_readonly("k", &Analysis::k)
      .def_property_readonly("grashof", [](const Analysis& a) { return std::string(to_string(a.grashof)); })
      .def_readonly("input_fully_rotates", &Analysis::input_fully_rotates)
      .def_readonly("dead_points", &Analysis::dead_points)
      .def_readonly("samples", &Analysis::samples)
      .def_readonly("transmission", &Analysis::transmission);
  m.def("analyze", &analyze, py::arg("bar"), py::arg("psi"), py::call_guard<py::gil_scoped_release>());
}

}  // namespace spdfit::python
