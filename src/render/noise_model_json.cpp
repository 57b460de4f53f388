// A noise model (Diagnostics::noise_model) as JSON and back: every field, so that a result that
// used one reads back with the same model.
#include <stdexcept>

#include "render/fit_result_json.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/render.hpp"

namespace spdfit::detail {

// NoiseModel's friend: its state has no public setters (the factories check and derive it).
struct NoiseModelJson {
  static Json write(const NoiseModel& m, JsonStyle style) {
    Json out;
    out["source"] = std::string(to_string(m.source_));
    if (m.cov_a_.size() > 0) out["cov_a"] = matrix_json(m.cov_a_, style);
    if (m.cov_b_.size() > 0) out["cov_b"] = matrix_json(m.cov_b_, style);
    if (m.std_a_.size() > 0) out["std_a"] = vector_json(m.std_a_, style);
    if (m.std_b_.size() > 0) out["std_b"] = vector_json(m.std_b_, style);
    if (m.rest_rows_) out["rest_rows"] = *m.rest_rows_;
    if (m.rest_mean_a_.size() > 0) out["rest_mean_a"] = vector_json(m.rest_mean_a_, style);
    if (m.rest_mean_b_.size() > 0) out["rest_mean_b"] = vector_json(m.rest_mean_b_, style);
    if (!m.rest_a_path_.empty()) out["rest_a_path"] = m.rest_a_path_;
    if (!m.rest_b_path_.empty()) out["rest_b_path"] = m.rest_b_path_;
    put_warnings(out, m.warnings_);
    return out;
  }

  static NoiseModel read(const Json& object, const std::string& type) {
    NoiseModel m;
    const auto source = value_from<std::string>(object, "source", type);
    bool known = false;
    for (NoiseSource s : {NoiseSource::Std, NoiseSource::Cov, NoiseSource::Rest}) {
      if (source == to_string(s)) m.source_ = s, known = true;
    }
    if (!known) throw std::invalid_argument(type + ": unknown noise source '" + source + "'");
    const auto matrix = [&](const char* key) {
      const Json* value = optional_field(object, key);
      return value ? matrix_from(*value, type + " '" + key + "'") : Eigen::MatrixXd();
    };
    const auto vector = [&](const char* key) {
      const Json* value = optional_field(object, key);
      return value ? vector_from(*value, type + " '" + key + "'") : Eigen::VectorXd();
    };
    m.cov_a_ = matrix("cov_a");
    m.cov_b_ = matrix("cov_b");
    m.std_a_ = vector("std_a");
    m.std_b_ = vector("std_b");
    if (optional_field(object, "rest_rows")) m.rest_rows_ = value_from<std::uint64_t>(object, "rest_rows", type);
    m.rest_mean_a_ = vector("rest_mean_a");
    m.rest_mean_b_ = vector("rest_mean_b");
    if (optional_field(object, "rest_a_path")) m.rest_a_path_ = value_from<std::string>(object, "rest_a_path", type);
    if (optional_field(object, "rest_b_path")) m.rest_b_path_ = value_from<std::string>(object, "rest_b_path", type);
    m.warnings_ = warnings_from(object, type);
    m.classify();  // zero and definite: derived from the covariances, as the factories derive them
    return m;
  }
};

Json noise_model_json(const NoiseModel& model, JsonStyle style) { return NoiseModelJson::write(model, style); }

NoiseModel noise_model_from(const Json& object, const std::string& type) { return NoiseModelJson::read(object, type); }

}  // namespace spdfit::detail

namespace spdfit {

std::string to_json(const NoiseModel& model, JsonStyle style) {
  return detail::dump(detail::noise_model_json(model, style), style);
}

template <>
NoiseModel from_json<NoiseModel>(const std::string& text) {
  return detail::noise_model_from(detail::parse_object(text, "NoiseModel"), "NoiseModel");
}

}  // namespace spdfit
