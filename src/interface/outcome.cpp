// The table of outcome codes and each front end's form of them.
#include "spdfit/outcome.hpp"

#include <cctype>
#include <new>

namespace spdfit {

namespace {

std::vector<CodeInfo> make_codes() {
  return {
      {Code::OptionType, "option_type", Tier::Usage, "an option's value of the wrong type"},
      {Code::OptionValue, "option_value", Tier::Usage, "an option's value out of its range or not one of its choices"},
      {Code::OptionNotApplicable, "option_not_applicable", Tier::Usage,
       "an option given where it does not apply (a method that does not take it)"},
      {Code::OptionConflict, "option_conflict", Tier::Usage,
       "options that exclude each other, or an option given without one it needs"},
      {Code::UnknownOption, "unknown_option", Tier::Usage, "an option the command or function does not have"},
      {Code::Argument, "argument", Tier::Usage, "a missing or malformed argument"},
      {Code::ColumnSelection, "column_selection", Tier::Usage,
       "columns or rows chosen that the file does not have, or a selection that cannot be read"},
      {Code::File, "file", Tier::Data, "a file that cannot be read, or whose text is not a table of numbers"},
      {Code::DataShape, "data_shape", Tier::Data, "sizes that do not fit (rows of A and B, a square matrix expected)"},
      {Code::DataValue, "data_value", Tier::Data, "values the method cannot take (NaN or Inf, a negative variance)"},
      {Code::NoiseModel, "noise_model_refused", Tier::Data,
       "a noise model the data refuse (a covariance not positive semidefinite or of another size, too few rest "
       "rows)"},
      {Code::Geometry, "geometry", Tier::Data, "a hexapod geometry that cannot be used"},
      {Code::PhysicalData, "physical_data", Tier::Data,
       "data that cannot identify what the physical fit estimates"},
      {Code::NumericalFailure, "numerical_failure", Tier::Numerical,
       "valid input without an answer; the message says why"},
      {Code::OutOfMemory, "out_of_memory", Tier::Internal, "out of memory"},
      {Code::Internal, "internal", Tier::Internal, "a fault of spdfit's own"},
      {Code::Warning, "warning", Tier::Warning, "a warning of no other kind"},
      {Code::FileNotice, "reader", Tier::Warning,
       "what a reader decided (a header row taken as names, an index column dropped)"},
      {Code::RankDeficient, "rank_deficient", Tier::Warning, "A or B (or a regressor) is rank-deficient"},
      {Code::IllConditioned, "ill_conditioned", Tier::Warning, "A (or a regressor) is ill-conditioned"},
      {Code::NotPositiveDefinite, "not_positive_definite", Tier::Warning,
       "an estimate that is not positive (semi)definite"},
      {Code::NotSymmetric, "not_symmetric", Tier::Warning, "an input or estimate that is not symmetric"},
      {Code::NotConverged, "not_converged", Tier::Warning, "an iterative method stopped before it converged"},
      {Code::EigenvaluesRaised, "eigenvalues_raised", Tier::Warning, "a repair's floor moved eigenvalues"},
      {Code::NoiseEstimate, "noise_estimate", Tier::Warning,
       "what the data say about their noise (too little, too much, unequal in A and B)"},
      {Code::NoiseModelNotice, "noise_model", Tier::Warning, "what a noise model says about the data"},
      {Code::Bias, "bias", Tier::Warning, "an estimator that is biased on these data; the message names a better one"},
      {Code::FewSamples, "few_samples", Tier::Warning, "fewer samples than the result needs to be trusted"},
      {Code::Boundary, "boundary", Tier::Warning,
       "an estimate on the boundary of the positive (semi)definite matrices"},
      {Code::BootstrapNotice, "bootstrap", Tier::Warning,
       "what the bootstrap could not do, or did differently"},
      {Code::PhysicalNotice, "physical", Tier::Warning,
       "the physical fit's notices (a parameter at its bound, a nominal value far off)"},
      {Code::LinkageNotice, "linkage", Tier::Warning, "a linkage design's or synthesis' notices"},
      {Code::Outliers, "outliers", Tier::Warning,
       "rows that dominate a fit: values of magnitude 1e30 or more (a logger's codes for invalid readings), rows "
       "whose studentized residual is far out among all rows' (gross errors, wrong values in A)"},
      {Code::DiagonalChanged, "diagonal_changed", Tier::Warning,
       "a repair changed the diagonal: variances below `min_diag` raised to it, or a covariance repaired to a unit "
       "diagonal"},
  };
}

std::string camel(std::string_view name, bool upper_first) {
  std::string out;
  bool upper = upper_first;
  for (char c : name) {
    if (c == '_') {
      upper = true;
      continue;
    }
    out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

}  // namespace

const std::vector<CodeInfo>& outcome_codes() {
  static const std::vector<CodeInfo> codes = make_codes();
  return codes;
}

const CodeInfo& code_info(Code code) {
  const std::vector<CodeInfo>& codes = outcome_codes();
  const auto index = static_cast<std::size_t>(code);
  if (index < codes.size() && codes[index].code == code) return codes[index];
  for (const CodeInfo& info : codes) {
    if (info.code == code) return info;
  }
  return codes[static_cast<std::size_t>(Code::Internal)];
}

std::optional<Code> code_named(std::string_view name) {
  for (const CodeInfo& info : outcome_codes()) {
    if (info.name == name) return info.code;
  }
  return std::nullopt;
}

int exit_status(Code code) {
  switch (tier(code)) {
    case Tier::Usage: return 2;
    case Tier::Warning: return 0;
    default: return 1;
  }
}

std::string python_class(Code code) {
  switch (tier(code)) {
    case Tier::Usage: return code == Code::OptionType || code == Code::UnknownOption ? "TypeError" : "ValueError";
    case Tier::Data: return "DataError";
    case Tier::Numerical: return "NumericalError";
    case Tier::Internal: return code == Code::OutOfMemory ? "MemoryError" : "RuntimeError";
    case Tier::Warning: break;
  }
  if (code == Code::Warning) return "SpdfitWarning";
  return camel(code_info(code).name, true) + "Warning";
}

std::string matlab_identifier(Code code) {
  switch (tier(code)) {
    case Tier::Usage: return "spdfit:UsageError";
    case Tier::Data: return "spdfit:DataError";
    case Tier::Numerical: return "spdfit:NumericalError";
    case Tier::Internal: return code == Code::OutOfMemory ? "spdfit:OutOfMemory" : "spdfit:Error";
    case Tier::Warning: break;
  }
  return "spdfit:" + camel(code_info(code).name, false);
}

std::vector<std::string> texts(const std::vector<Warning>& warnings) {
  std::vector<std::string> out;
  out.reserve(warnings.size());
  for (const Warning& w : warnings) out.push_back(w.text);
  return out;
}

void Problem::raise() const {
  if (tier(code) == Tier::Usage) throw OptionError(message, code, subject);
  throw InputError(message, code, subject);
}

Code code_of(const std::exception& error) noexcept {
  if (const auto* coded = dynamic_cast<const Coded*>(&error)) return coded->code();
  if (dynamic_cast<const std::bad_alloc*>(&error) != nullptr) return Code::OutOfMemory;
  if (dynamic_cast<const std::invalid_argument*>(&error) != nullptr) return Code::DataValue;
  return Code::Internal;
}

std::string subject_of(const std::exception& error) {
  if (const auto* coded = dynamic_cast<const Coded*>(&error)) return coded->subject();
  return {};
}

}  // namespace spdfit
