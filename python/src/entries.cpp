#include "entries.hpp"

#include <stdexcept>

#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/hexapod/physical_request.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/linkage/analyze_request.hpp"
#include "spdfit/linkage/synthesize_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit::python {

namespace {

bool contains(const std::vector<std::string_view>& names, std::string_view name) {
  for (std::string_view n : names) {
    if (n == name) return true;
  }
  return false;
}

template <typename Request>
std::vector<Keyword> keywords_of(const std::vector<OptionSpec<Request>>& table, const Entry& entry,
                                 const Request* applies_to, const Request& defaults = Request{}) {
  std::vector<Keyword> out;
  for (const OptionSpec<Request>& spec : table) {
    if (spec.python.empty() || spec.positional || contains(entry.unavailable, spec.name) || contains(entry.implied, spec.name)) continue;
    if (applies_to && spec.applies && !spec.applies(*applies_to)) continue;
    bool reachable = spec.needs.empty();
    for (std::string_view need : spec.needs) reachable = reachable || !contains(entry.unavailable, need);
    if (!reachable) continue;
    std::optional<OptionValue> default_value;
    if (!spec.nullable && spec.get) default_value = spec.get(defaults);
    out.push_back({spec.name, spec.python, spec.type, spell_options(spec.help, Frontend::Python), spec.default_text,
                   std::move(default_value), spec.nullable});
  }
  return out;
}

}  // namespace

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      // fit's a_cols and b_cols (columns of a DataFrame) are spelled out in Python, not the table's text.
      // rows, rest_rows and time_col are the command line's: arrays and DataFrames are sliced in Python.
      {"fit", "fit", {}, {"stream", "a_cols", "b_cols", "rows", "rest_rows", "time_col"}},
      // fit_files streams: rows, rest_rows and time_col choose rows of a fit in memory (slice in Python), and
      // robust reweighs rows in memory (spdfit.fit on the arrays).
      {"fit_files", "fit", {"stream"}, {"rows", "rest_rows", "time_col", "robust", "robust_tuning"}},
      {"fit_all", "fit", {}, {"stream", "bootstrap", "a_cols", "b_cols", "rows", "rest_rows", "time_col"}},
      // A factor holds the data in their units already (no scale_a, scale_b), of [A B] (no offsets),
      // and no rows to reweigh (no robust).
      {"Factor.fit", "fit", {}, {"stream", "bootstrap", "a_cols", "b_cols", "scale_a", "scale_b", "rows", "rest_rows", "time_col",
                                  "offsets", "robust", "robust_tuning"}},
      // A and B are positional; a_cols and b_cols (columns of a DataFrame) are spelled out in Python.
      {"hexapod.identify", "identify", {}, {"a", "b", "a_cols", "b_cols", "rows", "rest_rows", "time_col"}},
      {"physical.identify", "physical_fit", {}, {}},
      // The truth is an array or a geometry (Python's own forms); the command line's directory.
      {"hexapod.simulate", "simulate", {}, {"truth", "out"}},
      {"nearest_spd", "nearest", {}, {"corr", "factors", "factors_only"}},
      {"nearest_correlation", "nearest", {"corr"}, {"keep_diag", "via_corr"}},
      // The covariance repair keeps the variances; the correlation route (via_corr) is nearest_spd's.
      {"nearest_covariance", "nearest", {"keep_diag"}, {"corr", "via_corr", "factors", "factors_only"}},
      {"payload.identify", "payload", {}, {}},
      {"payload.design", "payload_design", {}, {}},
      {"physical.regress", "regress", {}, {}},
      // The body and the URDF's text are arguments; the result is returned, not written.
      {"physical.inertia_repair", "inertia_repair", {}, {"output"}},
      {"physical.inertia_repair_urdf", "inertia_repair", {}, {"output"}},
      // The experiments: the truth (thesis) and the sweep's levels are Python's own arguments.
      {"experiment.thesis", "experiment:thesis", {}, {}},
      {"experiment.paper_hexapod", "experiment:paper-hexapod", {}, {}},
      {"experiment.paper_2x2", "experiment:paper-2x2", {}, {"sweep"}},
      {"experiment.paper_2x2_sweep", "experiment:paper-2x2", {"sweep"}, {"std_a"}},
      {"experiment.physical", "experiment:physical", {}, {}},
      // The linkage: psi and phi (the pairs' columns), analyze's lengths and psi, and radians (every
      // angle, where the command line's --radians is the pairs file's) are Python's own arguments.
      {"linkage.synthesize", "linkage_synthesize", {}, {}},
      {"linkage.analyze", "linkage_analyze", {}, {}},
  };
  return list;
}

std::optional<experiment::ExperimentKind> experiment_kind(const Entry& entry) {
  for (experiment::ExperimentKind kind : experiment::kExperimentKinds) {
    if (entry.table == "experiment:" + std::string(experiment::to_string(kind))) return kind;
  }
  return std::nullopt;
}

const Entry& entry(std::string_view name) {
  for (const Entry& e : entries()) {
    if (e.name == name) return e;
  }
  throw std::invalid_argument("no Python entry named '" + std::string(name) + "'");
}

std::vector<Keyword> keywords(const Entry& entry, std::optional<Method> method) {
  if (entry.table == "nearest") return keywords_of(nearest_option_table(), entry, static_cast<NearestRequest*>(nullptr));
  if (entry.table == "payload") {
    return keywords_of(payload::identify_option_table(), entry, static_cast<payload::IdentifyRequest*>(nullptr));
  }
  if (entry.table == "payload_design") {
    return keywords_of(payload::design_option_table(), entry, static_cast<payload::DesignRequest*>(nullptr));
  }
  if (entry.table == "regress") {
    return keywords_of(physical::regress_option_table(), entry, static_cast<physical::RegressRequest*>(nullptr));
  }
  if (entry.table == "simulate") {
    return keywords_of(hexapod::simulate_option_table(), entry, static_cast<hexapod::SimulateRequest*>(nullptr));
  }
  if (const std::optional<experiment::ExperimentKind> kind = experiment_kind(entry)) {
    return keywords_of(experiment::experiment_option_table(*kind), entry,
                       static_cast<experiment::ExperimentRequest*>(nullptr), experiment::experiment_request(*kind));
  }
  if (entry.table == "linkage_synthesize") {
    return keywords_of(linkage::synthesize_option_table(), entry, static_cast<linkage::SynthesizeRequest*>(nullptr));
  }
  if (entry.table == "linkage_analyze") {
    return keywords_of(linkage::analyze_option_table(), entry, static_cast<linkage::AnalyzeRequest*>(nullptr));
  }
  if (entry.table == "inertia_repair") {
    return keywords_of(inertia_repair_option_table(), entry, static_cast<InertiaRepairRequest*>(nullptr));
  }
  if (entry.table == "physical") {
    return keywords_of(hexapod::physical_option_table(), entry,
                       static_cast<hexapod::PhysicalOptions*>(nullptr));
  }
  if (entry.table == "physical_fit") {
    return keywords_of(hexapod::physical_fit_table(), entry, static_cast<hexapod::PhysicalRequest*>(nullptr));
  }
  if (entry.table == "identify") {
    return keywords_of(hexapod::identify_option_table(), entry, static_cast<hexapod::IdentifyRequest*>(nullptr));
  }
  FitRequest request;
  if (method) request.method = *method;
  return keywords_of(fit_option_table(), entry, method ? &request : nullptr);
}

std::vector<Keyword> keywords(std::string_view name) {
  constexpr std::string_view kFitMethod = "fit:";
  if (name.substr(0, kFitMethod.size()) == kFitMethod) {
    const std::optional<Method> method = parse_method(name.substr(kFitMethod.size()));
    if (!method) throw std::invalid_argument("no method named '" + std::string(name.substr(kFitMethod.size())) + "'");
    return keywords(entry("fit"), method);
  }
  return keywords(entry(name));
}

std::string annotation(const Keyword& keyword) {
  std::string type;
  switch (keyword.type) {
    case OptionType::Flag:
    case OptionType::Boolean:
      type = "bool";
      break;
    case OptionType::Integer:
      type = "int";
      break;
    case OptionType::Real:
      type = "float";
      break;
    case OptionType::Text:
      type = "str";
      break;
    case OptionType::Names:
      type = "Union[str, Sequence[str]]";
      break;
    case OptionType::RealList:
      type = "Union[float, Sequence[float]]";
      break;
    case OptionType::Vector:
      type = "npt.ArrayLike";
      break;
    case OptionType::Noise:
      type = "NoiseModel";
      break;
    case OptionType::Choice:
      type = "str";
      break;
    case OptionType::File:
      type = "Union[str, os.PathLike]";
      break;
    case OptionType::Matrix:
      type = "npt.ArrayLike";
      break;
    case OptionType::Range:
      type = "Union[str, Tuple[float, float]]";
      break;
    case OptionType::Columns:
    case OptionType::Rows:
      type = "Union[str, Sequence[Union[str, int]]]";
      break;
    case OptionType::Geometry:
      type = "Union[Geometry, str, os.PathLike]";
      break;
  }
  return keyword.nullable ? "Optional[" + type + "]" : type;
}

}  // namespace spdfit::python
