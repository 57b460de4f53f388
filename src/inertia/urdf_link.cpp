// A body as a URDF <link> (inertia_repair.hpp's urdf_link): the export of the physical fits.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "spdfit/inertia_repair.hpp"

namespace spdfit {

namespace {

std::string number(double value, int precision) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", precision, value == 0.0 ? 0.0 : value);
  return buffer;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string urdf_link(const RigidBodyInertia& body, const std::string& name, int precision) {
  if (precision < 1 || precision > 17) {
    throw std::invalid_argument("`precision` must be an integer in [1, 17] (significant digits), got " +
                                std::to_string(precision));
  }
  std::string error;
  if (!is_well_formed(body, &error)) throw std::invalid_argument("cannot write a URDF link: " + error);
  const Eigen::Matrix3d I = 0.5 * (body.inertia + body.inertia.transpose());
  const auto n = [precision](double v) { return number(v, precision); };
  const Eigen::Vector3d& c = body.center_of_mass;
  return "<link name=\"" + escaped(name) + "\">\n" +
         "  <inertial>\n" +
         "    <origin xyz=\"" + n(c(0)) + " " + n(c(1)) + " " + n(c(2)) + "\" rpy=\"0 0 0\"/>\n" +
         "    <mass value=\"" + n(body.mass) + "\"/>\n" +
         "    <inertia ixx=\"" + n(I(0, 0)) + "\" ixy=\"" + n(I(0, 1)) + "\" ixz=\"" + n(I(0, 2)) + "\" iyy=\"" +
         n(I(1, 1)) + "\" iyz=\"" + n(I(1, 2)) + "\" izz=\"" + n(I(2, 2)) + "\"/>\n" +
         "  </inertial>\n" +
         "</link>\n";
}

}  // namespace spdfit
