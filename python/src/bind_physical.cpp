// spdfit.physical: physical identification of a hexapod's payload and rigid-body inertia repair;
// python/spdfit/physical.py is the public face. Results cross as the library's JSON (the same keys
// as the command line's), which the Python side turns into NumPy arrays.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "keywords.hpp"
#include "spdfit/inertia_repair.hpp"

namespace py = pybind11;

namespace spdfit::python {

using namespace spdfit::hexapod;

namespace {

RigidBodyInertia body_of(double mass, const Eigen::Vector3d& center_of_mass, const Eigen::Matrix3d& inertia) {
  RigidBodyInertia body;
  body.mass = mass;
  body.center_of_mass = center_of_mass;
  body.inertia = inertia;
  return body;
}

/// The repair's options from a Python call's keywords, through `inertia repair`'s table.
InertiaRepairOptions repair_options(std::string_view entry, const py::dict& options) {
  std::vector<std::string_view> given;
  return inertia_repair_request(entry, options, given).options;
}

}  // namespace

void bind_physical(py::module_& parent) {
  py::module_ m = parent.def_submodule("physical", "Physical identification of a hexapod payload; inertia repair.");

  // The physical fit's workflow (physical_request.hpp): the request from the keywords through its
  // table, its rules, its run; the estimate as its JSON (the Python side makes a PhysicalEstimate).
  m.def(
      "identify",
      [](const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const std::optional<Geometry>& geometry,
         const py::dict& options) {
        PhysicalRequest request;
        request.a.values = A;
        request.b.values = B;
        if (geometry) request.geometry.value = std::make_shared<const Geometry>(*geometry);
        std::vector<std::string_view> given;
        request = request_from(physical_fit_table(), entry("physical.identify"), options, std::move(request), given);
        check_physical_request(request, given);
        std::string text;
        {
          py::gil_scoped_release release;
          text = physical_json(run_physical(request));
        }
        return text;
      },
      py::arg("A"), py::arg("B"), py::arg("geometry"), py::arg("options"));

  m.def(
      "design",
      [](const Geometry& geometry, const std::string& strut_masses) {
        const auto struts = parse_strut_masses(strut_masses);
        if (!struts) {
          throw std::invalid_argument("strut_masses must be 'geometry', 'common' or 'each', got '" + strut_masses + "'");
        }
        const PhysicalDesign d = physical_design(geometry, *struts);
        py::dict out;
        out["parameters"] = d.parameters;
        out["rank"] = d.rank;
        out["condition"] = d.condition;
        out["length_scale"] = d.length_scale;
        out["null_space"] = d.null_space;
        out["confounded"] = d.confounded;
        return out;
      },
      py::arg("geometry"), py::arg("strut_masses"));

  m.def(
      "mass_matrix",
      [](const Geometry& geometry, double mass, const Eigen::Vector3d& center_of_mass, const Eigen::Matrix3d& inertia) {
        return Eigen::MatrixXd(joint_space_mass_matrix(geometry, body_of(mass, center_of_mass, inertia)));
      },
      py::arg("geometry"), py::arg("mass"), py::arg("center_of_mass"), py::arg("inertia"));

  m.def(
      "repair_inertia",
      [](double mass, const Eigen::Vector3d& center_of_mass, const Eigen::Matrix3d& inertia, const py::dict& options) {
        return inertia_repair_json(repair_inertia(body_of(mass, center_of_mass, inertia),
                                                  repair_options("physical.inertia_repair", options)));
      },
      py::arg("mass"), py::arg("center_of_mass"), py::arg("inertia"), py::arg("options"));

  m.def(
      "repair_urdf",
      [](const std::string& text, const std::string& source, const py::dict& options) {
        const UrdfRepairResult r = repair_urdf(text, source, repair_options("physical.inertia_repair_urdf", options));
        py::list links;
        for (const UrdfLinkRepair& l : r.links) {
          py::dict link;
          link["link"] = l.link;
          link["line"] = l.line;
          link["changed"] = l.result.changed;
          link["distance"] = l.result.distance;
          link["mass"] = l.result.repaired.mass;
          link["center_of_mass"] = Eigen::Vector3d(l.result.repaired.center_of_mass);
          link["inertia_before"] = Eigen::Matrix3d(l.result.input.inertia);
          link["inertia"] = Eigen::Matrix3d(l.result.repaired.inertia);
          links.append(link);
        }
        return py::make_tuple(r.text, urdf_repair_report(r), links);
      },
      py::arg("text"), py::arg("source"), py::arg("options"));
}

}  // namespace spdfit::python
