// solve's result as JSON: `spdfit solve --json`, and every field for pickles.
#include <stdexcept>

#include "render/json_values.hpp"

namespace spdfit {

using detail::Json;

namespace {

Json column_json(const ColumnClassification& c, JsonStyle style) {
  return {{"consistent", c.consistent},
          {"finite_solution_dimension", c.finite_solution_dimension},
          {"at_infinity_dimension", c.at_infinity_dimension},
          {"augmented_rank", c.augmented_rank},
          {"residual_norm", detail::number_json(c.residual_norm, style)},
          {"backward_error", detail::number_json(c.backward_error, style)}};
}

ColumnClassification column_from(const Json& object, const std::string& type) {
  ColumnClassification c;
  c.consistent = detail::value_from<bool>(object, "consistent", type);
  c.finite_solution_dimension = detail::value_from<Eigen::Index>(object, "finite_solution_dimension", type);
  c.at_infinity_dimension = detail::value_from<Eigen::Index>(object, "at_infinity_dimension", type);
  c.augmented_rank = detail::value_from<Eigen::Index>(object, "augmented_rank", type);
  c.residual_norm = detail::number_from(detail::field(object, "residual_norm", type), type + " 'residual_norm'");
  c.backward_error = detail::number_from(detail::field(object, "backward_error", type), type + " 'backward_error'");
  return c;
}

const SystemShape kShapes[] = {SystemShape::Underdetermined, SystemShape::Determined, SystemShape::Overdetermined};

}  // namespace

std::string to_json(const ColumnClassification& column, JsonStyle style) {
  return detail::dump(column_json(column, style), style);
}

template <>
ColumnClassification from_json<ColumnClassification>(const std::string& text) {
  return column_from(detail::parse_object(text, "ColumnClassification"), "ColumnClassification");
}

std::string to_json(const LinearSystemResult& r, JsonStyle style) {
  using detail::number_json;
  Json out;
  out["consistent"] = r.consistent;
  out["rank"] = r.rank;
  out["nullity"] = r.nullity;
  out["finite_solution_dimension"] = r.finite_solution_dimension;
  out["at_infinity_dimension"] = r.at_infinity_dimension;
  out["condition_number"] = number_json(r.condition_number, style);
  // One right-hand side: x as a flat list; several: X (n x p) as rows, as `fit` prints X.
  const bool flat = r.p == 1 && r.solution.cols() == 1;
  out["solution"] = flat ? detail::vector_json(r.solution.col(0), style) : detail::matrix_json(r.solution, style);
  out["residual_norm"] = number_json(r.residual_norm, style);
  out["null_space"] = detail::columns_json(r.null_space, style);
  out["range"] = detail::columns_json(r.range, style);
  out["m"] = r.m;
  out["n"] = r.n;
  out["shape"] = to_string(r.shape);
  out["singular_values"] = detail::vector_json(r.singular_values, style);
  out["threshold"] = r.rank_tolerance;  // the JSON keeps its key
  out["reciprocal_condition_number"] = number_json(r.reciprocal_condition_number, style);
  out["effective_condition_number"] = number_json(r.effective_condition_number, style);
  out["scaled_singular_values"] = detail::vector_json(r.scaled_singular_values, style);
  out["scaled_condition_number"] = number_json(r.scaled_condition_number, style);
  out["rank_decided_on"] = "column-scaled";
  out["refinement_steps"] = r.refinement_steps;
  Json columns = Json::array();
  for (std::size_t j = 0; j < r.columns.size(); ++j) {
    Json c = column_json(r.columns[j], style);
    const auto k = static_cast<Eigen::Index>(j);
    c["solution"] = k < r.solution.cols() ? detail::vector_json(r.solution.col(k), style) : Json::array();
    columns.push_back(std::move(c));
  }
  out["columns"] = columns;
  out["explanation"] = r.explanation;
  detail::put_warnings(out, r.warnings);
  if (style == JsonStyle::Exact) {
    out["status"] = r.ok() ? "success" : "numerical_failure";
    out["message"] = r.message;
    out["p"] = r.p;
  }
  return detail::dump(out, style);
}

template <>
LinearSystemResult from_json<LinearSystemResult>(const std::string& text) {
  const std::string type = "LinearSystemResult";
  const Json object = detail::parse_object(text, type);
  const auto number = [&](const char* key) {
    return detail::number_from(detail::field(object, key, type), type + " '" + key + "'");
  };
  const auto vector = [&](const char* key) {
    return detail::vector_from(detail::field(object, key, type), type + " '" + key + "'");
  };
  LinearSystemResult r;
  r.m = detail::value_from<Eigen::Index>(object, "m", type);
  r.n = detail::value_from<Eigen::Index>(object, "n", type);
  const Json& columns = detail::field(object, "columns", type);
  if (!columns.is_array()) throw std::invalid_argument(type + ": 'columns' is not an array");
  for (const Json& c : columns) r.columns.push_back(column_from(c, type + " column"));
  r.p = detail::optional_field(object, "p") ? detail::value_from<Eigen::Index>(object, "p", type)
                                    : static_cast<Eigen::Index>(r.columns.size());
  if (const Json* status = detail::optional_field(object, "status")) {
    const std::string name = status->is_string() ? status->get<std::string>() : "";
    if (name != "success" && name != "numerical_failure") {
      throw std::invalid_argument(type + ": unknown status " + status->dump());
    }
    r.status = name == "success" ? SolveStatus::Success : SolveStatus::NumericalFailure;
  }
  if (detail::optional_field(object, "message")) r.message = detail::value_from<std::string>(object, "message", type);
  const auto shape = detail::value_from<std::string>(object, "shape", type);
  bool known = false;
  for (SystemShape s : kShapes) {
    if (shape == to_string(s)) r.shape = s, known = true;
  }
  if (!known) throw std::invalid_argument(type + ": unknown shape '" + shape + "'");
  r.singular_values = vector("singular_values");
  r.rank_tolerance = number("threshold");
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  r.threshold = r.rank_tolerance;
#pragma GCC diagnostic pop
  r.rank = detail::value_from<Eigen::Index>(object, "rank", type);
  r.nullity = detail::value_from<Eigen::Index>(object, "nullity", type);
  r.condition_number = number("condition_number");
  r.reciprocal_condition_number = number("reciprocal_condition_number");
  r.effective_condition_number = number("effective_condition_number");
  r.scaled_singular_values = vector("scaled_singular_values");
  r.scaled_condition_number = number("scaled_condition_number");
  r.refinement_steps = detail::value_from<int>(object, "refinement_steps", type);
  r.consistent = detail::value_from<bool>(object, "consistent", type);
  r.finite_solution_dimension = detail::value_from<Eigen::Index>(object, "finite_solution_dimension", type);
  r.at_infinity_dimension = detail::value_from<Eigen::Index>(object, "at_infinity_dimension", type);
  const Json& solution = detail::field(object, "solution", type);
  const bool flat = !solution.empty() && solution.front().is_array() == false;
  r.solution = flat ? Eigen::MatrixXd(detail::vector_from(solution, type + " 'solution'"))
                    : detail::matrix_from(solution, type + " 'solution'");
  r.residual_norm = number("residual_norm");
  r.null_space = detail::columns_from(detail::field(object, "null_space", type), type + " 'null_space'", r.n);
  r.range = detail::columns_from(detail::field(object, "range", type), type + " 'range'", r.m);
  r.explanation = detail::value_from<std::string>(object, "explanation", type);
  r.warnings = detail::warnings_from(object, type);
  return r;
}

}  // namespace spdfit
