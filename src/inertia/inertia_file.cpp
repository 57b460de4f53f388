// Rigid-body inertia files (JSON) in: one body or a list of bodies. Every error names the file and
// the key. The repair's JSON out is render/inertia_render.cpp's.
#include <string>

#include <nlohmann/json.hpp>

#include "io/json_document.hpp"
#include "io/read_file.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"

namespace spdfit {

namespace {

using nlohmann::json;

// An inertia file is a few hundred bytes.
constexpr std::size_t kMaxInertiaBytes = std::size_t{1} << 20;

constexpr const char* kKeyList = "mass, center_of_mass, inertia";

// The keys inertia_repair_json (render/inertia_render.cpp) adds: its output reads back as input (and is repaired again,
// unchanged), so they are accepted and ignored.
bool is_repair_key(const std::string& key) {
  for (const char* k : {"changed", "distance", "certificate", "min_eig", "principal_moments",
                        "principal_moments_before", "second_moments_before", "metric", "warnings", "warning_codes"}) {
    if (key == k) return true;
  }
  return false;
}

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
  throw io::DataError(source, 0, 0, problem);
}

double number(const json& value, const std::string& where, const std::string& source) {
  if (!value.is_number()) fail(source, where + " must be a number, found " + io::detail::describe_json(value));
  return value.get<double>();
}

Eigen::Vector3d vector3(const json& value, const std::string& where, const std::string& source) {
  if (!value.is_array() || value.size() != 3) {
    fail(source, where + " must be [x, y, z] (3 numbers), found " + io::detail::describe_json(value));
  }
  return {number(value[0], where + "[0]", source), number(value[1], where + "[1]", source),
          number(value[2], where + "[2]", source)};
}

const json& require(const json& root, const char* key, const char* what, const std::string& source) {
  const auto it = root.find(key);
  if (it == root.end()) fail(source, std::string("missing key \"") + key + "\" (" + what + ")");
  return *it;
}

}  // namespace

namespace {

// A body from its JSON object; `where` prefixes the keys in messages ("" for a whole file,
// "bodies[2]." in a list).
RigidBodyInertia body_from(const json& root, const std::string& source, const std::string& where, bool strict_keys) {
  if (!root.is_object()) {
    fail(source, (where.empty() ? std::string("an inertia file") : where.substr(0, where.size() - 1)) +
                     " must hold a JSON object {\"mass\": m, \"center_of_mass\": [x, y, z], \"inertia\": [[3x3]]}; found " +
                     io::detail::describe_json(root));
  }
  if (strict_keys) {
    for (const auto& item : root.items()) {
      const std::string& key = item.key();
      if (!key.empty() && key[0] == '_') continue;  // comments
      if (key != "mass" && key != "center_of_mass" && key != "inertia" && !is_repair_key(key)) {
        fail(source, "unknown key \"" + where + key + "\" (the keys are " + kKeyList +
                         "; keys starting with '_' are ignored)");
      }
    }
  }
  RigidBodyInertia body;
  body.mass = number(require(root, "mass", "the body's mass in kg", source), where + "mass", source);
  body.center_of_mass = vector3(require(root, "center_of_mass", "the centre of mass [x, y, z] in metres", source),
                                where + "center_of_mass", source);
  const json& inertia = require(root, "inertia", "the 3x3 inertia tensor about the centre of mass, kg m^2", source);
  if (inertia.is_null()) {
    fail(source, where + "inertia is null: the data did not determine it (static poses determine only the mass and "
                         "the centre of mass)");
  }
  if (!inertia.is_array() || inertia.size() != 3) {
    fail(source, where + "inertia must be a 3x3 matrix [[a, b, c], [d, e, f], [g, h, i]]; found " +
                     io::detail::describe_json(inertia));
  }
  for (int i = 0; i < 3; ++i) {
    body.inertia.row(i) =
        vector3(inertia[i], where + "inertia[" + std::to_string(i) + "]", source).transpose();
  }
  std::string error;
  if (!is_well_formed(body, &error)) fail(source, where + error);
  return body;
}

}  // namespace

RigidBodyInertia parse_rigid_body(const std::string& text, const std::string& source) {
  // XML where a JSON body was expected: a URDF named otherwise, or a xacro file (URDF macros).
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '<') {
    const bool xacro = text.find("xacro") != std::string::npos;
    fail(source, xacro ? "is a xacro file (macros that make a URDF), not a JSON body: expand it first (xacro " + source +
                             " > robot.urdf) and repair robot.urdf"
                       : "is XML, not a JSON body: a URDF file is read as one when its name ends in .urdf or .xml");
  }
  const json root = io::detail::parse_json_document(text, source, kMaxInertiaBytes, "an inertia file", 4);
  // The JSON of `spdfit hexapod identify --physical --json`: its "physical" object; of `spdfit
  // payload identify --json`: its own top-level keys (it has "force_bias").
  if (root.is_object() && root.contains("physical") && root["physical"].is_object()) {
    return body_from(root["physical"], source, "physical.", false);
  }
  if (root.is_object() && root.contains("force_bias")) return body_from(root, source, "", false);
  return body_from(root, source, "", true);
}

std::vector<RigidBodyInertia> parse_rigid_bodies(const std::string& text, const std::string& source) {
  const json root = io::detail::parse_json_document(text, source, kMaxInertiaBytes, "a file of bodies", 4);
  const json* list = &root;
  std::string prefix = "";
  if (root.is_object() && root.contains("bodies")) {
    list = &root["bodies"];
    prefix = "bodies";
  }
  if (!list->is_array() || list->empty()) {
    fail(source, "a file of bodies must hold a non-empty JSON list of bodies [{\"mass\", \"center_of_mass\", "
                 "\"inertia\"}, ...] (or {\"bodies\": [...]}); found " + io::detail::describe_json(*list));
  }
  std::vector<RigidBodyInertia> out;
  for (std::size_t k = 0; k < list->size(); ++k) {
    out.push_back(body_from((*list)[k], source, prefix + "[" + std::to_string(k) + "].", true));
  }
  return out;
}

std::vector<RigidBodyInertia> read_rigid_bodies(const std::string& path) {
  return parse_rigid_bodies(io::detail::read_file(path, kMaxInertiaBytes, "a file of bodies"), path);
}

RigidBodyInertia read_rigid_body(const std::string& path) {
  return parse_rigid_body(io::detail::read_file(path, kMaxInertiaBytes, "an inertia file"), path);
}

}  // namespace spdfit
