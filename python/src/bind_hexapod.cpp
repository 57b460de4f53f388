// spdfit.hexapod: the Stewart platform model (thesis 000 ch. 2), the thesis' measurement
// generator (appendix B) and identification; python/spdfit/hexapod.py is the public face.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pickle.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/hexapod/simulation_warnings.hpp"
#include "spdfit/random.hpp"

namespace py = pybind11;

namespace spdfit::python {

using namespace spdfit::hexapod;

namespace {

// Every NoiseDistribution, for unpickling it by name (pickle.hpp).
constexpr std::array<NoiseDistribution, 2> kNoiseDistributions = {NoiseDistribution::Uniform,
                                                                  NoiseDistribution::Gaussian};

}  // namespace

void bind_hexapod(py::module_& parent) {
  py::module_ m = parent.def_submodule("hexapod", "Hexapod model, simulation and identification.");

  py::class_<Geometry>(m, "Geometry", "A Stewart platform's geometry and masses (SI units).")
      .def_property_readonly("base_points", copied(&Geometry::base_points), "3 x 6, one column per strut, in {B} (m)")
      .def_property_readonly("payload_points", copied(&Geometry::payload_points), "3 x 6, in {P} (m)")
      .def_property_readonly("payload_origin", copied(&Geometry::payload_origin))
      .def_property_readonly("payload_rotation", copied(&Geometry::payload_rotation))
      .def_property_readonly("payload_mass", copied(&Geometry::payload_mass))
      .def_property_readonly("payload_inertia", copied(&Geometry::payload_inertia))
      .def_property_readonly("strut_mass", copied(&Geometry::strut_mass))
      .def_property_readonly("strut_stiffness", copied(&Geometry::strut_stiffness))
      .def_property_readonly("strut_damping", copied(&Geometry::strut_damping))
      .def("to_json", &geometry_json, "The geometry in the geometry-file format (JSON text).")
      .def(pickle_fields<Geometry>(
          "Geometry", state_field(&Geometry::base_points), state_field(&Geometry::payload_points),
          state_field(&Geometry::payload_origin), state_field(&Geometry::payload_rotation),
          state_field(&Geometry::payload_mass), state_field(&Geometry::payload_inertia),
          state_field(&Geometry::strut_mass), state_field(&Geometry::strut_stiffness),
          state_field(&Geometry::strut_damping)));

  m.def("cubic_geometry", []() { return cubic_geometry(); },
        "The built-in cubic-configuration hexapod (mutually orthogonal struts).");
  m.def("read_geometry", &read_geometry, py::arg("path"));
  m.def("parse_geometry", &parse_geometry, py::arg("text"), py::arg("source") = "<geometry>");
  m.def("joint_space_mass_matrix", py::overload_cast<const Geometry&>(&joint_space_mass_matrix), py::arg("geometry"));
  py::class_<ModelDescription>(m, "ModelDescription", "What hexapod::describe reports about a hexapod.")
      .def_property_readonly("jacobian", copied(&ModelDescription::jacobian))
      .def_property_readonly("jacobian_condition", copied(&ModelDescription::jacobian_condition))
      .def_property_readonly("payload_mass_matrix", copied(&ModelDescription::payload_mass_matrix))
      .def_property_readonly("mass_matrix", copied(&ModelDescription::mass_matrix))
      .def_property_readonly("mass_matrix_eigenvalues", copied(&ModelDescription::mass_matrix_eigenvalues))
      .def_property_readonly("modes_hz", copied(&ModelDescription::modes_hz))
      .def_property_readonly("strut_lengths", copied(&ModelDescription::strut_lengths))
      .def_property_readonly("strut_directions", copied(&ModelDescription::strut_directions))
      .def(pickle_fields<ModelDescription>(
          "ModelDescription", state_field(&ModelDescription::jacobian),
          state_field(&ModelDescription::jacobian_condition), state_field(&ModelDescription::payload_mass_matrix),
          state_field(&ModelDescription::mass_matrix), state_field(&ModelDescription::mass_matrix_eigenvalues),
          state_field(&ModelDescription::modes_hz), state_field(&ModelDescription::strut_lengths),
          state_field(&ModelDescription::strut_directions)));
  m.def("describe", &describe, py::arg("geometry"));
  m.def("thesis_mass_matrix", &thesis_mass_matrix, "M_p of thesis eq. 6.1.");

  py::class_<SimulationOptions>(m, "SimulationOptions",
                                "The generator's settings; the defaults are the thesis' chapter-6 set-up.")
      .def(py::init<>())
      .def_property_readonly("samples", copied(&SimulationOptions::samples))
      .def_property_readonly("noise_var", copied(&SimulationOptions::noise_var))
      .def_property_readonly("force_noise_var", copied(&SimulationOptions::force_noise_var),
                             "the noise variance in B when it differs from A's (None: noise_var)")
      .def_property_readonly("signal_var", copied(&SimulationOptions::signal_var))
      .def_property_readonly("distribution",
                             [](const SimulationOptions& o) { return std::string(to_string(o.distribution)); })
      .def_property_readonly("noise_std_a", copied(&SimulationOptions::noise_std_a),
                             "standard deviations of the noise in A, one or one per column (None: noise_var)")
      .def_property_readonly("noise_std_b", copied(&SimulationOptions::noise_std_b),
                             "the same for B, in B's units before scale_b (None: force_noise_var or noise_var)")
      .def_property_readonly("rest_samples", copied(&SimulationOptions::rest_samples),
                             "rows recorded at rest drawn after the data (0: none)")
      .def_property_readonly("rest_force", copied(&SimulationOptions::rest_force),
                             "the force at rest, one per column of B (empty: truth times (1, ..., 1))")
      .def_property_readonly("scale_b", copied(&SimulationOptions::scale_b),
                             "the factor B is multiplied by after it is drawn (0.001: newtons to kilonewtons)")
      .def(pickle_fields<SimulationOptions>(
          "SimulationOptions", state_field(&SimulationOptions::samples), state_field(&SimulationOptions::noise_var),
          state_field(&SimulationOptions::force_noise_var), state_field(&SimulationOptions::signal_var),
          enum_field(&SimulationOptions::distribution, kNoiseDistributions, "SimulationOptions", "distribution"),
          state_field(&SimulationOptions::noise_std_a), state_field(&SimulationOptions::noise_std_b),
          state_field(&SimulationOptions::rest_samples), state_field(&SimulationOptions::rest_force),
          state_field(&SimulationOptions::scale_b)));

  m.def(
      "simulate",
      [](std::optional<Eigen::MatrixXd> truth, const py::dict& options) {
        std::vector<std::string_view> given;
        SimulateRequest request = simulate_request("hexapod.simulate", options, given);
        if (truth) {
          request.truth.values = *truth;
          given.push_back("truth");
        }
        check_simulate_request(request, given);
        const SimulateResult r = run_simulate(request);  // as `spdfit hexapod simulate`
        return py::make_tuple(r.data.A, r.data.B, Eigen::MatrixXd(r.truth * r.options.scale_b), r.data.A_true,
                              r.data.B_true, r.data.rest_A, r.data.rest_B, r.warnings);
      },
      py::arg("truth"), py::arg("options"));

  py::class_<MethodIdentification>(m, "MethodIdentification")
      .def_property_readonly("result", copied(&MethodIdentification::result))
      .def_property_readonly("eigenvalues", copied(&MethodIdentification::eigenvalues))
      .def_property_readonly("modes_hz", copied(&MethodIdentification::modes_hz))
      .def_property_readonly("error_vs_truth", copied(&MethodIdentification::error_vs_truth))
      .def_property_readonly("modes_uncertainty", copied(&MethodIdentification::modes_uncertainty),
                             "with bootstrap=N and a stiffness: the modes' SpectrumUncertainty")
      .def(pickle_json<MethodIdentification>(
          "MethodIdentification",
          [](const MethodIdentification& method, JsonStyle style) { return hexapod::to_json(method, style); }))
      .def("__repr__", [](const MethodIdentification& method) {
        return "MethodIdentification(method='" + std::string(to_string(method.result.method)) + "')\n" +
               report(method.result, python_report_hints());
      });
  // hexapod identify's workflow (identify_request.hpp): the request from the keywords through its
  // table, its rules, its run; (methods, the physical estimate's JSON or None, every warning).
  m.def(
      "identify",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const py::dict& options) {
        IdentifyRequest request;
        request.a.values = A;
        request.b.values = B;
        std::vector<std::string_view> given;
        request = request_from(identify_option_table(), entry("hexapod.identify"), options, std::move(request), given);
        check_identify_request(request, given);
        Identification result;
        {
          py::gil_scoped_release release;
          result = run_identify(request);
        }
        std::optional<std::string> physical_text;
        if (result.physical) physical_text = to_json(*result.physical, result.options);
        return py::make_tuple(result.methods, physical_text, result.warnings);
      },
      py::arg("A"), py::arg("B"), py::arg("options"));
}

}  // namespace spdfit::python
