// `hexapod model`'s result as JSON (the geometry's own document inside) and as a report for people.
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "render/json_values.hpp"
#include "render/text_values.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/model_request.hpp"

namespace spdfit::hexapod {

std::string to_json(const ModelResult& result) {
  using spdfit::detail::matrix_json;
  using spdfit::detail::vector_json;
  constexpr JsonStyle style = JsonStyle::Contract;
  const ModelDescription& model = result.model;
  nlohmann::json out;
  out["geometry_source"] = result.geometry_source;
  out["jacobian"] = matrix_json(model.jacobian, style);
  out["mass_matrix"] = matrix_json(model.mass_matrix, style);
  out["modes_hz"] = vector_json(model.modes_hz, style);
  out["mass_matrix_eigenvalues"] = vector_json(model.mass_matrix_eigenvalues, style);
  out["jacobian_condition"] = spdfit::detail::number_json(model.jacobian_condition, style);
  out["payload_mass_matrix"] = matrix_json(model.payload_mass_matrix, style);
  out["strut_lengths"] = vector_json(model.strut_lengths, style);
  out["strut_directions"] = matrix_json(model.strut_directions.transpose(), style);
  out["geometry"] = nlohmann::json::parse(geometry_json(result.geometry));
  return spdfit::detail::dump(out, style);
}

std::string report(const ModelResult& result) {
  const ModelDescription& model = result.model;
  std::ostringstream out;
  out << "Hexapod: " << result.geometry_source << "\n"
      << "payload " << format_fixed(result.geometry.payload_mass, 3)
      << " kg; strut lengths (m): " << spdfit::detail::fixed_values(model.strut_lengths, 4) << "\n\n"
      << "Jacobian J, l_dot = J [v; w] (rows: struts; v, w of the payload's centre of mass in {B} axes); "
      << "cond(J) = " << format_fixed(model.jacobian_condition, 2) << "\n"
      << format_side_by_side({"J"}, {Eigen::MatrixXd(model.jacobian)})
      << "Joint-space mass-inertia matrix (thesis eq. 2.12), kg\n"
      << format_side_by_side({"M_p"}, {Eigen::MatrixXd(model.mass_matrix)})
      << "eigenvalues of M_p (kg): " << spdfit::detail::fixed_values(model.mass_matrix_eigenvalues, 4)
      << "\nmodes sqrt(eig(M_p^-1 K)) / 2 pi (Hz), K = diag(strut_stiffness): " << spdfit::detail::fixed_values(model.modes_hz, 2)
      << "\n";
  return out.str();
}

}  // namespace spdfit::hexapod
