// spdfit.linkage: four-bar function-generator synthesis and analysis (notes 002, 3.3-3.6).
// Angles are radians here; python/spdfit/linkage.py offers degrees.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pickle.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/analyze_request.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/grashof.hpp"
#include "spdfit/linkage/prescribed_function.hpp"
#include "spdfit/linkage/status.hpp"
#include "spdfit/linkage/synthesis.hpp"
#include "spdfit/linkage/synthesize_request.hpp"

namespace py = pybind11;

namespace spdfit::python {

using namespace spdfit::linkage;

namespace {

// The enumerators of the enums pickled by name (pickle.hpp).
constexpr std::array<GrashofType, 6> kGrashofTypes = {GrashofType::CrankRocker,  GrashofType::RockerCrank,
                                                      GrashofType::DoubleCrank,  GrashofType::DoubleRocker,
                                                      GrashofType::ChangePoint, GrashofType::TripleRocker};
constexpr std::array<SynthesisStatus, 4> kSynthesisStatuses = {
    SynthesisStatus::Success, SynthesisStatus::NoRealLinkage, SynthesisStatus::NotAssemblable,
    SynthesisStatus::Diverged};

// GaussNewtonOptions.threshold as Python has it: the rank tolerance, negative for the default rule.
double gauss_newton_threshold(const GaussNewtonOptions& options) { return options.rank_tolerance.value_or(-1.0); }
void set_gauss_newton_threshold(GaussNewtonOptions& options, double value) {
  options.rank_tolerance = value < 0.0 ? std::nullopt : std::optional<double>(value);
}

}  // namespace

void bind_linkage(py::module_& parent) {
  py::module_ m = parent.def_submodule("linkage", "Four-bar synthesis and analysis (radians).");

  py::class_<FourBar>(m, "FourBar", "Link lengths: a1 ground, a2 input, a3 coupler, a4 output.")
      .def(py::init([](double a1, double a2, double a3, double a4) { return FourBar{a1, a2, a3, a4}; }),
           py::arg("a1"), py::arg("a2"), py::arg("a3"), py::arg("a4"))
      .def_property_readonly("a1", copied(&FourBar::a1))
      .def_property_readonly("a2", copied(&FourBar::a2))
      .def_property_readonly("a3", copied(&FourBar::a3))
      .def_property_readonly("a4", copied(&FourBar::a4))
      .def(pickle_fields<FourBar>("FourBar", state_field(&FourBar::a1), state_field(&FourBar::a2),
                                  state_field(&FourBar::a3), state_field(&FourBar::a4)))
      .def("__repr__", [](const FourBar& b) {
        std::ostringstream out;
        out << "FourBar(a1=" << b.a1 << ", a2=" << b.a2 << ", a3=" << b.a3 << ", a4=" << b.a4 << ")";
        return out.str();
      });

  py::class_<AngleRange>(m, "AngleRange")
      .def_property_readonly("min", copied(&AngleRange::min))
      .def_property_readonly("max", copied(&AngleRange::max))
      .def(pickle_fields<AngleRange>("AngleRange", state_field(&AngleRange::min), state_field(&AngleRange::max)));
  py::class_<DialZeros>(m, "DialZeros")
      .def_property_readonly("alpha", copied(&DialZeros::alpha))
      .def_property_readonly("beta", copied(&DialZeros::beta))
      .def(pickle_fields<DialZeros>("DialZeros", state_field(&DialZeros::alpha), state_field(&DialZeros::beta)));

  py::class_<MotionCheck>(m, "MotionCheck")
      .def_property_readonly("grashof", [](const MotionCheck& c) { return std::string(to_string(c.grashof)); })
      .def_property_readonly("transmission", copied(&MotionCheck::transmission))
      .def_property_readonly("dead_points", copied(&MotionCheck::dead_points))
      .def_property_readonly("branch_defect", copied(&MotionCheck::branch_defect))
      .def_property_readonly("branch_defect_reason", copied(&MotionCheck::branch_defect_reason))
      .def(pickle_fields<MotionCheck>(
          "MotionCheck", enum_field(&MotionCheck::grashof, kGrashofTypes, "MotionCheck", "Grashof type"),
          state_field(&MotionCheck::transmission), state_field(&MotionCheck::dead_points),
          state_field(&MotionCheck::branch_defect), state_field(&MotionCheck::branch_defect_reason)));

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
      .def_property_readonly("rounding_limited", copied(&LinkageSolution::rounding_limited),
                             "Gauss-Newton stopped at rounding level above the tolerance")
      .def_property_readonly("check", copied(&LinkageSolution::check))
      .def(pickle_fields<LinkageSolution>(
          "LinkageSolution", state_field(&LinkageSolution::k), state_field(&LinkageSolution::dial_zeros),
          state_field(&LinkageSolution::lengths), state_field(&LinkageSolution::no_linkage_reason),
          state_field(&LinkageSolution::design_error_norm), state_field(&LinkageSolution::structural_error_rms),
          state_field(&LinkageSolution::structural_error_max), state_field(&LinkageSolution::phi_generated),
          state_field(&LinkageSolution::iterations), state_field(&LinkageSolution::final_step_norm),
          state_field(&LinkageSolution::rounding_limited), state_field(&LinkageSolution::check)));

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
      .def_property_readonly("warnings", warning_texts(&SynthesisResult::warnings))
      .def_property_readonly("warning_codes", warning_codes(&SynthesisResult::warnings), "each warning's code (spdfit.outcome_codes())")
      .def(pickle_fields<SynthesisResult>(
          "SynthesisResult", enum_field(&SynthesisResult::status, kSynthesisStatuses, "SynthesisResult", "status"),
          state_field(&SynthesisResult::message), state_field(&SynthesisResult::positions),
          state_field(&SynthesisResult::precision_point), state_field(&SynthesisResult::dial_zeros_fitted),
          state_field(&SynthesisResult::branch), state_field(&SynthesisResult::rank),
          state_field(&SynthesisResult::condition_number), state_field(&SynthesisResult::scaled_condition_number),
          state_field(&SynthesisResult::used_svd), state_field(&SynthesisResult::psi),
          state_field(&SynthesisResult::phi), state_field(&SynthesisResult::design),
          state_field(&SynthesisResult::structural), state_field(&SynthesisResult::warnings)));

  py::class_<GaussNewtonOptions>(m, "GaussNewtonOptions",
                                 "Gauss-Newton on the structural error; the defaults are the library's.")
      .def(py::init<>())
      .def_readwrite("tolerance", &GaussNewtonOptions::tolerance)
      .def_readwrite("max_iterations", &GaussNewtonOptions::max_iterations)
      .def_property("threshold", &gauss_newton_threshold, &set_gauss_newton_threshold,
                    "relative singular-value cut-off of each step (negative: max(m, n) eps)")
      .def(pickle_fields<GaussNewtonOptions>(
          "GaussNewtonOptions", state_field(&GaussNewtonOptions::tolerance),
          state_field(&GaussNewtonOptions::max_iterations),
          state_field(&gauss_newton_threshold, [](GaussNewtonOptions& options, const py::object& value) {
            set_gauss_newton_threshold(options, value.cast<double>());
          })));

  // `linkage synthesize` and `linkage analyze`'s workflows (synthesize_request.hpp,
  // analyze_request.hpp): the request from the keywords through the command's table, its rules and
  // its run, as the command line runs them.
  m.attr("STEERING_PSI_RANGE") = py::make_tuple(kSteeringPsiRange[0], kSteeringPsiRange[1]);
  m.def(
      "run_synthesize",
      [](const py::dict& options) {
        std::vector<std::string_view> given;
        const SynthesizeRequest request =
            request_from(synthesize_option_table(), entry("linkage.synthesize"), options, SynthesizeRequest{}, given);
        py::gil_scoped_release release;
        return run_synthesize(request, given).result;
      },
      py::arg("options"));
  m.def(
      "run_analyze",
      [](const std::vector<double>& lengths, const std::optional<Eigen::VectorXd>& psi, const py::dict& options) {
        std::vector<std::string_view> given;
        AnalyzeRequest request;
        request.lengths = lengths;
        if (psi) request.psi = *psi;
        request = request_from(analyze_option_table(), entry("linkage.analyze"), options, std::move(request), given);
        py::gil_scoped_release release;
        return run_analyze(request, given);
      },
      py::arg("lengths"), py::arg("psi"), py::arg("options"));
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
      .def_property_readonly("transmission_angle", copied(&AnalysisSample::transmission_angle))
      .def(pickle_fields<AnalysisSample>(
          "AnalysisSample", state_field(&AnalysisSample::psi), state_field(&AnalysisSample::phi_plus),
          state_field(&AnalysisSample::phi_minus), state_field(&AnalysisSample::transmission_angle)));
  py::class_<Analysis>(m, "Analysis")
      .def_property_readonly("bar", copied(&Analysis::bar))
      .def_property_readonly("k", copied(&Analysis::k))
      .def_property_readonly("grashof", [](const Analysis& a) { return std::string(to_string(a.grashof)); })
      .def_property_readonly("input_fully_rotates", copied(&Analysis::input_fully_rotates))
      .def_property_readonly("dead_points", copied(&Analysis::dead_points))
      .def_property_readonly("samples", copied(&Analysis::samples))
      .def_property_readonly("transmission", copied(&Analysis::transmission))
      .def(pickle_fields<Analysis>("Analysis", state_field(&Analysis::bar), state_field(&Analysis::k),
                                   enum_field(&Analysis::grashof, kGrashofTypes, "Analysis", "Grashof type"),
                                   state_field(&Analysis::input_fully_rotates), state_field(&Analysis::dead_points),
                                   state_field(&Analysis::samples), state_field(&Analysis::transmission)));
}

}  // namespace spdfit::python
