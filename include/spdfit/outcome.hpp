// Outcomes with codes: every error and warning the library reports carries a Code, the option or
// file it concerns and its text. Front ends map the code, never the text, to an exit status, a
// Python exception or warning class and a MATLAB identifier (outcome_codes() lists every code with
// those forms; docs/errors.md prints the same table).
#pragma once

#include <cstdint>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace spdfit {

/// The kinds of outcome, which decide what a front end does with one.
enum class Tier : std::uint8_t {
  Usage,      ///< the request is malformed (an option's value, a combination, an argument): exit 2
  Data,       ///< the data cannot be fitted as given (a bad file, NaN, sizes that do not fit): exit 1
  Numerical,  ///< valid input without an answer (a failed estimate): exit 1
  Internal,   ///< out of memory, or a fault of spdfit's own: exit 1
  Warning,    ///< a condition the user should know about; the result stands
};

/// Every outcome the library reports. The name each has in outcome_codes() ("rank_deficient") is
/// the stable form front ends build on: Python's class (RankDeficientWarning), MATLAB's
/// identifier (spdfit:rankDeficient). Add a code here and its row to outcome_codes() together.
enum class Code : std::uint16_t {
  // Usage
  OptionType,           ///< an option's value of the wrong type (Python: TypeError)
  OptionValue,          ///< an option's value out of its range or not one of its choices
  OptionNotApplicable,  ///< an option given where it does not apply (a method that does not take it)
  OptionConflict,       ///< options that exclude each other, or one given without what it needs
  UnknownOption,        ///< an option the function does not have (Python: TypeError)
  Argument,             ///< a missing or malformed argument (the command line's positional ones, ...)
  ColumnSelection,      ///< columns or rows chosen that the file does not have
  // Data
  File,                 ///< a file that cannot be read, or whose text is not a table of numbers
  DataShape,            ///< sizes that do not fit (rows of A and B, a square matrix expected, ...)
  DataValue,            ///< values the method cannot take (NaN or Inf, a negative variance, ...)
  NoiseModel,           ///< a noise model the data refuse (a covariance not PSD, of another size, ...)
  Geometry,             ///< a hexapod geometry that is not one (a file, a singular Jacobian, ...)
  PhysicalData,         ///< data that cannot identify what the physical fit estimates
  // Numerical
  NumericalFailure,     ///< valid input without an answer; the result's message says why
  // Internal
  OutOfMemory,
  Internal,
  // Warnings
  Warning,              ///< a warning of no other kind
  FileNotice,           ///< what a reader decided (a header taken as names, an index column dropped)
  RankDeficient,
  IllConditioned,
  NotPositiveDefinite,
  NotSymmetric,
  NotConverged,
  EigenvaluesRaised,    ///< a repair's floor moved eigenvalues
  NoiseEstimate,        ///< what the data say about their noise (too little, too much, unequal)
  NoiseModelNotice,     ///< what a noise model says (from rest rows, its sizes, ...)
  Bias,                 ///< an estimator biased on these data, a better one named
  FewSamples,           ///< fewer samples than the result needs to be trusted
  Boundary,             ///< an estimate on the boundary of the positive (semi)definite cone
  BootstrapNotice,      ///< what the bootstrap could not do, or did differently
  PhysicalNotice,       ///< the physical fit's notices (a parameter at its bound, a nominal far off)
  LinkageNotice,        ///< a linkage's design or synthesis notices
  Outliers,             ///< rows that dominate a fit: a logger's codes for invalid readings, gross errors
  DiagonalChanged,      ///< a repair changed the diagonal (variances raised to min_diag, a unit diagonal)
};

/// A code's forms and meaning.
struct CodeInfo {
  Code code;
  std::string_view name;     ///< snake_case, stable: "rank_deficient"
  Tier tier;
  std::string_view meaning;  ///< one line, for docs/errors.md
};

/// Every code, in the enum's order.
const std::vector<CodeInfo>& outcome_codes();

/// The row of `code`.
const CodeInfo& code_info(Code code);

/// The code named `name` (CodeInfo::name), or nothing.
std::optional<Code> code_named(std::string_view name);

/// The tier of `code`.
inline Tier tier(Code code) { return code_info(code).tier; }

/// The command line's exit status for an error of `code`: 2 for Usage, 1 otherwise (0 for a warning).
int exit_status(Code code);

/// Python's class for `code`: "TypeError" (OptionType, UnknownOption), "ValueError" (other usage),
/// "DataError", "NumericalError", "MemoryError", "RuntimeError", or for a warning its own class,
/// the name in CamelCase + "Warning" ("RankDeficientWarning"; Warning: "SpdfitWarning"), each a
/// subclass of spdfit.SpdfitWarning.
std::string python_class(Code code);

/// MATLAB's identifier for `code`: "spdfit:UsageError", "spdfit:DataError", "spdfit:NumericalError",
/// "spdfit:OutOfMemory", "spdfit:Error", or for a warning "spdfit:" + the name in lower camelCase
/// ("spdfit:rankDeficient"; Warning: "spdfit:warning").
std::string matlab_identifier(Code code);

/// A condition the user should know about: the result stands.
struct Warning {
  Code code = Code::Warning;
  std::string text;     ///< options named by their library names in backticks (spell_options)
  std::string subject;  ///< the option (library name) or file it concerns; empty when none

  Warning() = default;
  Warning(Code code_, std::string text_, std::string subject_ = {})
      : code(code_), text(std::move(text_)), subject(std::move(subject_)) {}

  bool operator==(const Warning& other) const {
    return code == other.code && text == other.text && subject == other.subject;
  }
};

/// The texts of `warnings`, in order.
std::vector<std::string> texts(const std::vector<Warning>& warnings);

/// The code and subject an error carries: a base of spdfit's exception types (OptionError,
/// InputError, io::DataError, io::ColumnSelectionError), found with code_of.
class Coded {
 public:
  Code code() const noexcept { return code_; }
  /// The option (library name), argument or file the error concerns; empty when none.
  const std::string& subject() const noexcept { return subject_; }

 protected:
  Coded(Code code, std::string subject) : code_(code), subject_(std::move(subject)) {}
  ~Coded() = default;
  Coded(const Coded&) = default;
  Coded& operator=(const Coded&) = default;

 private:
  Code code_;
  std::string subject_;
};

/// Data given in memory that the library cannot fit as given (NaN in A, sizes that do not fit, a
/// covariance that is not positive semidefinite): Tier::Data, like io::DataError for a file. A
/// std::invalid_argument, so that code catching that still catches it.
class InputError : public std::invalid_argument, public Coded {
 public:
  explicit InputError(const std::string& message, Code code = Code::DataValue, std::string subject = {})
      : std::invalid_argument(message), Coded(code, std::move(subject)) {}
};

/// A misused option: a value of the wrong type or out of range, an option the chosen method does
/// not take, or a combination the request's rules forbid (Tier::Usage; the code says which). The
/// message names options by their library names in backticks (`max_iterations`); a front end
/// shows it through spell_options (spelling.hpp). A std::invalid_argument: misuse of the API.
struct OptionError : std::invalid_argument, Coded {
  explicit OptionError(const std::string& message, Code code = Code::OptionValue, std::string option = {})
      : std::invalid_argument(message), Coded(code, std::move(option)) {}
};

/// What a check found, not yet thrown: raise() throws OptionError for a usage code, InputError
/// otherwise.
struct Problem {
  Code code = Code::DataValue;
  std::string message;
  std::string subject;

  [[noreturn]] void raise() const;
};

/// The code of an exception: its own (Coded), else DataValue for std::invalid_argument (the
/// library's refusal of input), OutOfMemory for std::bad_alloc, Internal for anything else.
Code code_of(const std::exception& error) noexcept;

/// The subject of an exception (Coded::subject), or empty.
std::string subject_of(const std::exception& error);

}  // namespace spdfit
