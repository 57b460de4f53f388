// `hexapod model`'s option table and workflow (its renderings: render/hexapod_model_render.cpp).
#include <sstream>

#include <nlohmann/json.hpp>

#include "interface/option_builders.hpp"
#include "render/json_values.hpp"
#include "render/text_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/model_request.hpp"

namespace spdfit::hexapod {

namespace {

using ModelSpec = OptionSpec<ModelRequest>;

constexpr const char* kBuiltInHexapod = "built-in cubic-configuration hexapod (docs/hexapod.md)";

std::vector<ModelSpec> make_model_table() {
  std::vector<ModelSpec> table;
  ModelSpec geometry = spdfit::detail::option_entry<ModelRequest>(
      "geometry", "--geometry", "", OptionType::Geometry, "FILE", "Geometry file (JSON, SI units; see docs/hexapod.md)",
      "the built-in cubic hexapod");
  geometry.set = [](ModelRequest& r, const OptionValue& v) { r.geometry = std::get<GeometryInput>(v); };
  table.push_back(geometry);
  for (ModelSpec& spec : output_options(&ModelRequest::output, {"json", "output"},
                                   {"Print everything as JSON, the geometry included (a template for a file)",
                                    "Write to FILE instead of stdout"})) {
    table.push_back(std::move(spec));
  }
  ModelSpec write = spdfit::detail::option_entry<ModelRequest>(
      "write_geometry", "--write-geometry", "", OptionType::File, "FILE",
      "Also write the geometry to FILE in the geometry-file format (a template to edit)");
  write.set = [](ModelRequest& r, const OptionValue& v) { r.write_geometry = std::get<std::string>(v); };
  table.push_back(write);
  return table;
}

}  // namespace

const std::vector<OptionSpec<ModelRequest>>& model_option_table() {
  static const std::vector<OptionSpec<ModelRequest>> table = make_model_table();
  return table;
}

ModelResult run_model(const ModelRequest& request) {
  ModelResult result;
  if (request.geometry.value) {
    result.geometry = *request.geometry.value;
    result.geometry_source = request.geometry.path.empty() ? "the geometry given" : request.geometry.path;
  } else if (!request.geometry.path.empty()) {
    result.geometry = read_geometry(request.geometry.path);
    result.geometry_source = request.geometry.path;
  } else {
    result.geometry = cubic_geometry();
    result.geometry_source = kBuiltInHexapod;
  }
  result.model = describe(result.geometry);
  return result;
}

}  // namespace spdfit::hexapod
