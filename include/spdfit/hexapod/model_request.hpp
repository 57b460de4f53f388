// `spdfit hexapod model`: the request (a geometry, or the built-in hexapod), its option table,
// the workflow and its renderings, so that every front end describes a hexapod the same way.
#pragma once

#include <string>
#include <vector>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"

namespace spdfit::hexapod {

/// What `hexapod model` describes and how it prints it.
struct ModelRequest {
  GeometryInput geometry;      ///< none: the built-in cubic-configuration hexapod
  std::string write_geometry;  ///< also write the geometry to this file (a template to edit); empty: not
  OutputRequest output;        ///< json, output
};

/// The options of `hexapod model`: geometry, json, output, write_geometry.
const std::vector<OptionSpec<ModelRequest>>& model_option_table();

/// A hexapod described: its geometry, where it came from and its model.
struct ModelResult {
  Geometry geometry;
  std::string geometry_source;  ///< the geometry file, or the built-in hexapod's description
  ModelDescription model;
};

/// The workflow of `hexapod model`: the geometry read (io::DataError naming the file) and
/// described. The geometry file of `write_geometry` is the caller's to write (geometry_json).
ModelResult run_model(const ModelRequest& request);

/// `hexapod model --json`: geometry_source, jacobian, jacobian_condition, mass_matrix,
/// mass_matrix_eigenvalues, modes_hz, payload_mass_matrix, strut_lengths, strut_directions (one
/// row per strut) and the geometry in the geometry file's format. Indented by 2, a final newline.
std::string to_json(const ModelResult& result);

/// `hexapod model`'s report for people: the payload and strut lengths, J with cond(J), M_p, its
/// eigenvalues and the modes.
std::string report(const ModelResult& result);

}  // namespace spdfit::hexapod
