// Reading and writing geometry files (JSON). Every error names the file and the key.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <string>

#include <Eigen/Cholesky>
#include <nlohmann/json.hpp>

#include "io/json_document.hpp"
#include "io/read_file.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/io.hpp"

namespace spdfit::hexapod {

namespace {

using nlohmann::json;

struct KeyInfo {
  const char* key;
  bool required;
  const char* what;  // for "missing key" messages
};

const KeyInfo kKeys[] = {
    {"base_points", true, "the six base joints [[x, y, z], ...] in {B}, metres"},
    {"payload_points", true,
     "the six payload joints [[x, y, z], ...] in {P}, metres from the centre of mass"},
    {"payload_origin", true, "{P}'s origin (the payload's centre of mass) in {B}, [x, y, z] metres"},
    {"payload_rotation", false, "{P}'s axes in {B}, a 3x3 rotation matrix"},
    {"payload_mass", true, "the payload's mass in kg"},
    {"payload_inertia", true, "the payload's 3x3 inertia tensor about its centre of mass, in {P}, kg m^2"},
    {"strut_mass", true, "the moving mass of each strut in kg, a number or [6 numbers]"},
    {"strut_stiffness", true, "the stiffness of each strut in N/m, a number or [6 numbers]"},
    {"strut_damping", false, "the damping of each strut in N s/m, a number or [6 numbers]"},
};

// Reads values out of the parsed document, throwing DataError naming the source and key.
class Reader {
 public:
  Reader(const json& root, std::string source) : root_(root), source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& problem) const { throw io::DataError(source_, 0, 0, problem); }

  const json* find(const char* key) const {
    const auto it = root_.find(key);
    return it == root_.end() ? nullptr : &*it;
  }

  const json& require(const char* key) const {
    if (const json* value = find(key)) return *value;
    for (const KeyInfo& info : kKeys) {
      if (std::string(info.key) == key) fail(std::string("missing key \"") + key + "\" (" + info.what + ")");
    }
    fail(std::string("missing key \"") + key + "\"");
  }

  double number(const json& value, const std::string& where) const {
    if (!value.is_number()) fail(where + " must be a number, found " + describe(value));
    return value.get<double>();
  }

  Eigen::Vector3d vector3(const json& value, const std::string& where) const {
    if (!value.is_array() || value.size() != 3)
      fail(where + " must be [x, y, z] (3 numbers), found " + describe(value));
    return {number(value[0], where + "[0]"), number(value[1], where + "[1]"),
            number(value[2], where + "[2]")};
  }

  Points points(const char* key) const {
    const json& value = require(key);
    if (!value.is_array() || value.size() != 6) {
      fail(std::string(key) + " must be an array of 6 points [[x, y, z], ...], one per strut; found " +
           describe(value));
    }
    Points p;
    for (int i = 0; i < 6; ++i)
      p.col(i) = vector3(value[i], std::string(key) + "[" + std::to_string(i) + "]");
    return p;
  }

  Eigen::Matrix3d matrix3(const json& value, const char* key) const {
    if (!value.is_array() || value.size() != 3) {
      fail(std::string(key) + " must be a 3x3 matrix [[a, b, c], [d, e, f], [g, h, i]]; found " +
           describe(value));
    }
    Eigen::Matrix3d M;
    for (int i = 0; i < 3; ++i) {
      M.row(i) = vector3(value[i], std::string(key) + "[" + std::to_string(i) + "]").transpose();
    }
    return M;
  }

  Vector6d per_strut(const json& value, const char* key) const {
    if (value.is_number()) return Vector6d::Constant(value.get<double>());
    if (!value.is_array() || value.size() != 6) {
      fail(std::string(key) +
           " must be a number (the same for every strut) or an array of 6 numbers; found " + describe(value));
    }
    Vector6d v;
    for (int i = 0; i < 6; ++i) v(i) = number(value[i], std::string(key) + "[" + std::to_string(i) + "]");
    return v;
  }

  static std::string describe(const json& value) { return io::detail::describe_json(value); }

 private:
  const json& root_;
  std::string source_;
};

// A geometry file is about 2 kB. The cap bounds the parser's memory, which is many times the
// text's for long arrays (each number becomes a JSON value), and is checked before reading.
constexpr std::size_t kMaxGeometryBytes = std::size_t{1} << 20;

}  // namespace

Geometry parse_geometry(const std::string& text, const std::string& source) {
  const json root = io::detail::parse_json_document(text, source, kMaxGeometryBytes, "a geometry file", 3);
  Reader in(root, source);
  if (!root.is_object()) in.fail("a geometry file must hold a JSON object {\"base_points\": ..., ...}");
  for (const auto& item : root.items()) {
    const std::string& key = item.key();
    if (!key.empty() && key[0] == '_') continue;  // comments
    const bool known = std::any_of(std::begin(kKeys), std::end(kKeys),
                                   [&key](const KeyInfo& info) { return key == info.key; });
    if (!known) {
      std::string names;
      for (const KeyInfo& info : kKeys) names += std::string(names.empty() ? "" : ", ") + info.key;
      in.fail("unknown key \"" + key + "\" (the keys are " + names + "; keys starting with '_' are ignored)");
    }
  }

  Geometry g;
  g.base_points = in.points("base_points");
  g.payload_points = in.points("payload_points");
  g.payload_origin = in.vector3(in.require("payload_origin"), "payload_origin");
  if (const json* rotation = in.find("payload_rotation"))
    g.payload_rotation = in.matrix3(*rotation, "payload_rotation");
  g.payload_mass = in.number(in.require("payload_mass"), "payload_mass");
  g.payload_inertia = in.matrix3(in.require("payload_inertia"), "payload_inertia");
  g.strut_mass = in.per_strut(in.require("strut_mass"), "strut_mass");
  g.strut_stiffness = in.per_strut(in.require("strut_stiffness"), "strut_stiffness");
  if (const json* damping = in.find("strut_damping"))
    g.strut_damping = in.per_strut(*damping, "strut_damping");

  std::string error;
  if (!g.is_valid(&error)) in.fail(error);
  // The masses and the inertia together: M_p, which every command computes (its Cholesky factor
  // for the modes), must be positive definite with entries whose squares are finite (a
  // payload_mass of 1e300 is not), named here with the file.
  const Matrix6d Mp = joint_space_mass_matrix(g);
  const double largest = Mp.allFinite() ? Mp.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
  const bool too_large = !(largest < std::sqrt(std::numeric_limits<double>::max()));
  if (too_large || Eigen::LLT<Matrix6d>(Mp).info() != Eigen::Success) {
    in.fail("payload_mass " + format_number(g.payload_mass) + " kg with this payload_inertia and strut_mass makes a " +
            "joint-space mass matrix M_p " +
            (too_large ? "with entries too large to compute with (up to " + format_number(largest) + ")"
                       : std::string("that is not positive definite")) +
            ": are they in kg and kg m^2?");
  }
  return g;
}

Geometry read_geometry(const std::string& path) {
  return parse_geometry(io::detail::read_file(path, kMaxGeometryBytes, "a geometry file"), path);
}

std::string geometry_json(const Geometry& g) {
  using ordered = nlohmann::ordered_json;
  auto points = [](const Points& p) {
    ordered out = ordered::array();
    for (int i = 0; i < 6; ++i) out.push_back({p(0, i), p(1, i), p(2, i)});
    return out;
  };
  auto matrix = [](const Eigen::Matrix3d& M) {
    ordered out = ordered::array();
    for (int i = 0; i < 3; ++i) out.push_back({M(i, 0), M(i, 1), M(i, 2)});
    return out;
  };
  auto per_strut = [](const Vector6d& v) {
    ordered out = ordered::array();
    for (int i = 0; i < 6; ++i) out.push_back(v(i));
    return out;
  };
  ordered out;
  out["base_points"] = points(g.base_points);
  out["payload_points"] = points(g.payload_points);
  out["payload_origin"] = {g.payload_origin.x(), g.payload_origin.y(), g.payload_origin.z()};
  out["payload_rotation"] = matrix(g.payload_rotation);
  out["payload_mass"] = g.payload_mass;
  out["payload_inertia"] = matrix(g.payload_inertia);
  out["strut_mass"] = per_strut(g.strut_mass);
  out["strut_stiffness"] = per_strut(g.strut_stiffness);
  out["strut_damping"] = per_strut(g.strut_damping);
  return out.dump(2) + "\n";
}

}  // namespace spdfit::hexapod
