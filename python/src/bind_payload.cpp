// spdfit.payload (identify, design) and spdfit.physical.regress: the bindings read their keywords
// from the library's option tables (entries.cpp: "payload.identify", "payload.design",
// "physical.regress"); python/spdfit/payload.py and physical.py are the public faces. Results cross
// as the library's JSON (the command line's keys), which the Python side turns into NumPy arrays.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "keywords.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "spdfit/option_spelling.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace py = pybind11;

namespace spdfit::python {

namespace {

// A result's warnings spelled for Python with the command's own table first (the JSON carries them).
template <typename Request>
void spell_warnings(std::vector<Warning>& warnings, const std::vector<OptionSpec<Request>>& table) {
  for (Warning& w : warnings) w.text = spell_options_with(w.text, Frontend::Python, table);
}

Eigen::MatrixXd matrix_of(const py::dict& arrays, const char* key) {
  if (!arrays.contains(key) || arrays[key].is_none()) return {};
  return arrays[key].cast<Eigen::MatrixXd>();
}

payload::PayloadSignals signals_of(const py::dict& arrays) {
  payload::PayloadSignals s;
  s.wrench = matrix_of(arrays, "wrench");
  s.quaternion = matrix_of(arrays, "quaternion");
  s.rotation = matrix_of(arrays, "rotation");
  s.gravity = matrix_of(arrays, "gravity_in_sensor");
  s.accel = matrix_of(arrays, "accel");
  s.specific_force = matrix_of(arrays, "specific_force");
  s.omega = matrix_of(arrays, "omega");
  s.alpha = matrix_of(arrays, "alpha");
  const Eigen::MatrixXd time = matrix_of(arrays, "time");
  if (time.size() > 0) s.time = Eigen::Map<const Eigen::VectorXd>(time.data(), time.size());
  return s;
}

}  // namespace

void bind_payload(py::module_& parent) {
  py::module_ m = parent.def_submodule("payload", "A payload on a wrist force/torque sensor.");

  // (json text, residuals): from a file (`path`) or from arrays (`arrays`: wrench, quaternion, ...).
  m.def(
      "identify",
      [](std::optional<std::string> path, const py::dict& arrays, const py::dict& options) {
        const auto& table = payload::identify_option_table();
        {
          std::vector<std::string_view> given;
          payload::IdentifyRequest request = payload_request("payload.identify", options, given);
          payload::check_identify_request(request, given);
          payload::PayloadEstimate estimate;
          if (path) {
            py::gil_scoped_release release;
            estimate = payload::identify_file(*path, request);
          } else {
            for (const char* name : {"wrench_cols", "quat_cols", "rotation_cols", "gravity_cols", "accel_cols",
                                     "specific_force_cols", "omega_cols", "alpha_cols", "time_col"}) {
              for (std::string_view g : given)
                if (g == name) {
                  throw OptionError("`" + std::string(name) +
                                        "` chooses columns of a log file; with arrays, pass the signal itself",
                                    Code::OptionNotApplicable, name);
                }
            }
            const payload::PayloadSignals signals = signals_of(arrays);
            py::gil_scoped_release release;
            estimate = payload::identify(signals, request);
          }
          spell_warnings(estimate.warnings, table);
          return py::make_tuple(payload::to_json(estimate), estimate.residuals, payload::report(estimate));
        }
      },
      py::arg("path"), py::arg("arrays"), py::arg("options"));

  m.def(
      "urdf",
      [](const std::string& json_text, const std::string& name, int precision) {
        // The URDF link of an estimate's JSON (mass, centre of mass, inertia).
        RigidBodyInertia body = parse_rigid_body(json_text, "the estimate");
        return urdf_link(body, name, precision);
      },
      py::arg("json_text"), py::arg("name"), py::arg("precision"));

  m.def(
      "design",
      [](std::optional<std::string> path, const py::dict& arrays, const py::dict& options) {
        const auto& table = payload::design_option_table();
        {
          std::vector<std::string_view> given;
          const payload::DesignRequest request = design_request("payload.design", options, given);
          payload::check_design_request(request, given);
          payload::DesignResult result;
          if (path) {
            py::gil_scoped_release release;
            result = payload::design_file(*path, request);
          } else {
            const payload::PayloadSignals signals = signals_of(arrays);
            py::gil_scoped_release release;
            result = payload::design(signals, request);
          }
          spell_warnings(result.warnings, table);
          return py::make_tuple(payload::to_json(result), payload::report(result));
        }
      },
      py::arg("path"), py::arg("arrays"), py::arg("options"));

  py::module_ physical = parent.attr("physical").cast<py::module_>();
  physical.def(
      "regress",
      [](const Eigen::MatrixXd& Y, const Eigen::MatrixXd& tau, std::optional<Eigen::MatrixXd> noise_cov,
         std::optional<std::vector<std::tuple<double, Eigen::Vector3d, Eigen::Matrix3d>>> prior, const py::dict& options) {
        const auto& table = physical::regress_option_table();
        {
          std::vector<std::string_view> given;
          physical::RegressRequest request = regress_request("physical.regress", options, given);
          // `prior` arrives as bodies beside the options: what needs it (prior_weight) or excludes
          // it (unconstrained) is checked as on the command line.
          if (prior) given.push_back("prior");
          physical::check_regress_request(request, given);
          if (noise_cov) request.noise_cov = *noise_cov;
          if (prior) {
            for (const auto& [mass, com, inertia] : *prior) {
              RigidBodyInertia body;
              body.mass = mass;
              body.center_of_mass = com;
              body.inertia = inertia;
              request.prior.push_back(body);
            }
          }
          physical::RegressResult result;
          {
            py::gil_scoped_release release;
            result = physical::regress(Y, tau, request);
          }
          spell_warnings(result.warnings, table);
          return py::make_tuple(physical::to_json(result), physical::report(result));
        }
      },
      py::arg("Y"), py::arg("tau"), py::arg("noise_cov"), py::arg("prior"), py::arg("options"));
}

}  // namespace spdfit::python
