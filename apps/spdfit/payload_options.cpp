// --payload-mass, --payload-com and --payload-inertia: parsing and checking the true payload.
#include "payload_options.hpp"

#include <initializer_list>
#include <vector>

#include "cli.hpp"
#include "spdfit/hexapod/model.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

void add_payload_options(CLI::App* sub, PayloadCli& payload, const std::string& whose) {
  payload.mass_option =
      sub->add_option("--payload-mass", payload.mass, whose + " mass (kg; default the geometry's)");
  payload.com_option = sub->add_option("--payload-com", payload.com,
                                       whose +
                                           " centre of mass x,y,z (m, {P}'s axes, from {P}'s "
                                           "origin, the nominal centre of mass; default 0,0,0)");
  payload.inertia_option = sub->add_option(
      "--payload-inertia", payload.inertia,
      whose +
          " inertia about its centre of mass ({P}'s axes, kg m^2): 3 numbers "
          "(the diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz as URDF orders them) or 9 (row by row); default the "
          "geometry's");
  payload.mass_option->type_name("KG");
  payload.com_option->type_name("X,Y,Z");
  payload.inertia_option->type_name("I");
}

namespace {

// The comma-separated numbers of option `spelling`, whose count must be one of `counts`.
std::vector<double> numbers(const std::string& spelling, const std::string& text,
                            std::initializer_list<std::size_t> counts, const std::string& expected) {
  const std::vector<double> values =
      std::get<std::vector<double>>(parse_option_text(OptionType::RealList, spelling, text));
  for (std::size_t c : counts) {
    if (values.size() == c) return values;
  }
  throw UsageError(spelling + ": give " + expected + ", not " + std::to_string(values.size()) + " numbers");
}

}  // namespace

RigidBodyInertia payload_of(const PayloadCli& cli, const hexapod::Geometry& geometry) {
  RigidBodyInertia body = hexapod::nominal_payload(geometry);
  if (cli.mass_option->count() > 0) body.mass = numbers("--payload-mass", cli.mass, {1}, "one number")[0];
  if (cli.com_option->count() > 0) {
    const std::vector<double> c = numbers("--payload-com", cli.com, {3}, "3 comma-separated numbers x,y,z");
    body.center_of_mass = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  if (cli.inertia_option->count() > 0) {
    const std::vector<double> v = numbers("--payload-inertia", cli.inertia, {3, 6, 9},
                                          "3 (the diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz) or 9 numbers");
    Eigen::Matrix3d I;
    if (v.size() == 3) {
      I = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
    } else if (v.size() == 6) {
      I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    } else {
      I << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
    }
    body.inertia = I;
  }
  std::string error;
  if (!is_well_formed(body, &error)) {
    const std::string option = error.rfind("mass", 0) == 0             ? "--payload-mass"
                               : error.rfind("center_of_mass", 0) == 0 ? "--payload-com"
                                                                       : "--payload-inertia";
    throw UsageError(option + ": " + error);
  }
  return body;
}

nlohmann::json payload_json(const RigidBodyInertia& body) {
  nlohmann::json inertia = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) inertia.push_back({body.inertia(i, 0), body.inertia(i, 1), body.inertia(i, 2)});
  return {{"mass", body.mass},
          {"center_of_mass", {body.center_of_mass(0), body.center_of_mass(1), body.center_of_mass(2)}},
          {"inertia", inertia}};
}

}  // namespace spdfit::cli
