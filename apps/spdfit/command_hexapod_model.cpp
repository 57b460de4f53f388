// spdfit hexapod model [--geometry G.json] [--json] [--write-geometry FILE] [-o FILE]: the Jacobian,
// the joint-space mass-inertia matrix M_p and the modes of a hexapod.
#include <memory>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "hexapod_commands.hpp"
#include "output.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"

namespace spdfit::cli {

namespace {

constexpr const char* kBuiltInName = "built-in cubic-configuration hexapod (docs/hexapod.md)";

hexapod::Geometry load_geometry(const std::string& path) {
  return path.empty() ? hexapod::cubic_geometry() : hexapod::read_geometry(path);
}

// The entries of v with `digits` decimals, two spaces apart.
std::string vector_text(const Eigen::VectorXd& v, int digits) {
  std::string out;
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? "  " : "") + format_fixed(v(i), digits);
  return out;
}

}  // namespace

Command add_hexapod_model(CLI::App& parent, const GlobalOptions&) {
  struct Cli {
    std::string geometry, output, write_geometry;
    bool json = false;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "model",
      "The Jacobian, the joint-space mass-inertia matrix M_p (thesis eq. 2.12) and the modes of a hexapod");
  sub->add_option("--geometry", cli->geometry,
                  "Geometry file (JSON, SI units; see docs/hexapod.md). Default: the built-in cubic hexapod");
  sub->add_flag("--json", cli->json,
                "Print everything as JSON, the geometry included (a template for a file)");
  sub->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");
  sub->add_option("--write-geometry", cli->write_geometry,
                  "Also write the geometry to FILE in the geometry-file format (a template to edit)");

  auto run = [cli]() {
    const hexapod::Geometry geometry = load_geometry(cli->geometry);
    if (!cli->write_geometry.empty()) {
      emit(hexapod::geometry_json(geometry), cli->write_geometry);
      // On stderr: stdout carries the model, which may be piped on.
      std::cerr << "spdfit: wrote the geometry to " << cli->write_geometry << " (edit it, then --geometry "
                << cli->write_geometry << ")\n";
    }
    const hexapod::ModelDescription model = hexapod::describe(geometry);
    const std::string source = cli->geometry.empty() ? kBuiltInName : cli->geometry;
    if (cli->json) {
      nlohmann::json out;
      out["geometry_source"] = source;
      out["jacobian"] = matrix_json(model.jacobian);
      out["mass_matrix"] = matrix_json(model.mass_matrix);
      out["modes_hz"] = vector_json(model.modes_hz);
      out["mass_matrix_eigenvalues"] = vector_json(model.mass_matrix_eigenvalues);
      out["jacobian_condition"] = number_json(model.jacobian_condition);
      out["payload_mass_matrix"] = matrix_json(model.payload_mass_matrix);
      out["strut_lengths"] = vector_json(model.strut_lengths);
      out["strut_directions"] = matrix_json(model.strut_directions.transpose());
      out["geometry"] = nlohmann::json::parse(hexapod::geometry_json(geometry));
      emit(out.dump(2) + "\n", cli->output);
      return;
    }
    std::ostringstream out;
    out << "Hexapod: " << source << "\n"
        << "payload " << format_fixed(geometry.payload_mass, 3)
        << " kg; strut lengths (m): " << vector_text(model.strut_lengths, 4) << "\n\n"
        << "Jacobian J, l_dot = J [v; w] (rows: struts; v, w of the payload's centre of mass in {B} axes); "
        << "cond(J) = " << format_fixed(model.jacobian_condition, 2) << "\n"
        << format_side_by_side({"J"}, {Eigen::MatrixXd(model.jacobian)})
        << "Joint-space mass-inertia matrix (thesis eq. 2.12), kg\n"
        << format_side_by_side({"M_p"}, {Eigen::MatrixXd(model.mass_matrix)})
        << "eigenvalues of M_p (kg): " << vector_text(model.mass_matrix_eigenvalues, 4)
        << "\nmodes sqrt(eig(M_p^-1 K)) / 2 pi (Hz), K = diag(strut_stiffness): " << vector_text(model.modes_hz, 2)
        << "\n";
    emit(out.str(), cli->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
