// Results rendered once, for every front-end: JSON for programs (the command line's --json, the
// Python module's pickles) and text reports for people (the command line's --report and tables,
// Python's repr). The JSON is returned as text, so that this header does not tie a program to
// the JSON library spdfit is built with.
#pragma once

#include <string>

#include "spdfit/compare.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/nearest_spd.hpp"

namespace spdfit {

/// The two JSON renderings of a result.
enum class JsonStyle {
  /// The documented contract (docs/cli.md, what `spdfit ... --json` prints): the keys listed there,
  /// +-inf and NaN as null (JSON has no literal for them), indented by 2 with a final newline.
  Contract,
  /// Every field, +-inf and NaN as the strings "inf", "-inf" and "nan", on one line: from_json
  /// gives back the same object, every double bit for bit (but a NaN's payload). For pickles and
  /// caches; a superset of Contract's keys.
  Exact,
};

/// The result as JSON text (see JsonStyle). The keys of FitResult's are cli.md's fit contract:
/// method, status, m, n, d, X, diagnostics, warnings, error (failed only), row_names and
/// column_names (when known), and with a bootstrap standard_errors, interval, bias and bootstrap.
/// Cost O(size of the result).
std::string to_json(const FitResult& result, JsonStyle style = JsonStyle::Contract);
/// The parts of a FitResult on their own (the same objects as inside it; a Diagnostics also
/// carries m, n and d, and a Bootstrap its standard_errors, interval and bias).
std::string to_json(const Diagnostics& diagnostics, JsonStyle style = JsonStyle::Contract);
std::string to_json(const PsdCertificate& certificate, JsonStyle style = JsonStyle::Contract);
std::string to_json(const BoundaryCertificate& certificate, JsonStyle style = JsonStyle::Contract);
std::string to_json(const AutoReason& reason, JsonStyle style = JsonStyle::Contract);
std::string to_json(const Interval& interval, JsonStyle style = JsonStyle::Contract);
std::string to_json(const SpectrumUncertainty& spectrum, JsonStyle style = JsonStyle::Contract);
std::string to_json(const Bootstrap& bootstrap, JsonStyle style = JsonStyle::Contract);
/// A repair's result: n, X, distance, clipped, min_eig, min_eigenvalue_before, iterations,
/// gradient_norm, converged, cholesky (cholesky_ok) and warnings.
std::string to_json(const NearestResult& result, JsonStyle style = JsonStyle::Contract);
/// solve's result as `spdfit solve --json` prints it (one right-hand side: the solution as a flat
/// list); Exact adds status, message and p.
std::string to_json(const LinearSystemResult& result, JsonStyle style = JsonStyle::Contract);
std::string to_json(const ColumnClassification& column, JsonStyle style = JsonStyle::Contract);
/// `spdfit compare --json`: m, n, d and the results, each with its error_vs_truth.
std::string to_json(const Comparison& comparison, JsonStyle style = JsonStyle::Contract);
/// A noise model, as a FitResult's diagnostics hold it: source, cov_a, cov_b, std_a, std_b,
/// rest_rows, rest_mean_a, rest_mean_b, rest_a_path, rest_b_path (each where it has a value) and
/// warnings.
std::string to_json(const NoiseModel& model, JsonStyle style = JsonStyle::Contract);

/// The object that to_json wrote, from its text in either style (Contract's null reads as NaN, so
/// a Contract text loses the sign of an infinity; keys Contract leaves out take their defaults).
/// Defined for FitResult, Diagnostics, PsdCertificate, BoundaryCertificate, AutoReason, Interval,
/// SpectrumUncertainty, Bootstrap, NoiseModel, NearestResult, LinearSystemResult,
/// ColumnClassification and hexapod::MethodIdentification; and (declared beside their to_json)
/// hexapod::PhysicalEstimate, InertiaRepairResult, physical::RegressResult, payload::PayloadEstimate,
/// payload::DesignResult and experiment::PhysicalExperimentResult. Throws std::invalid_argument, naming the class and the field,
/// for text that is not such a document. Cost O(length of the text).
template <typename T>
T from_json(const std::string& text);

template <> FitResult from_json<FitResult>(const std::string& text);
template <> Diagnostics from_json<Diagnostics>(const std::string& text);
template <> PsdCertificate from_json<PsdCertificate>(const std::string& text);
template <> BoundaryCertificate from_json<BoundaryCertificate>(const std::string& text);
template <> AutoReason from_json<AutoReason>(const std::string& text);
template <> Interval from_json<Interval>(const std::string& text);
template <> SpectrumUncertainty from_json<SpectrumUncertainty>(const std::string& text);
template <> Bootstrap from_json<Bootstrap>(const std::string& text);
template <> NoiseModel from_json<NoiseModel>(const std::string& text);
template <> NearestResult from_json<NearestResult>(const std::string& text);
template <> LinearSystemResult from_json<LinearSystemResult>(const std::string& text);
template <> ColumnClassification from_json<ColumnClassification>(const std::string& text);

/// What a report says about the caller's own means, which differ between front-ends; the
/// defaults name the library's option and the JSON rendering.
struct ReportHints {
  /// How to ask for a bootstrap, after "X (no standard errors: " (the command line: "add
  /// --bootstrap N, e.g. 1000").
  std::string bootstrap = "set `bootstrap` to N, e.g. 1000";
  /// Where the percentile intervals and the bias are, after "... and the bias estimate: ".
  std::string details = "to_json (interval, bias)";
};

/// `spdfit fit --report`: X (with its bootstrap standard errors, when there are any), its
/// eigenvalues (with their intervals), the noise estimate and how auto chose; a failed result
/// says why. Cost O(n d).
std::string report(const FitResult& result, const ReportHints& hints = {});
/// Sorted values with their bootstrap intervals, one line each, each line starting with
/// `indent`, clusters marked: "  1  3.6527 +- 0.021   [3.61, 3.70]".
std::string report(const SpectrumUncertainty& spectrum, const std::string& indent = "");
/// `spdfit solve`: the explanation, the rank and condition numbers, the solutions and bases.
std::string report(const LinearSystemResult& result);
/// `spdfit compare`: the data, the estimates side by side, and a table of their diagnostics and
/// errors.
std::string report(const Comparison& comparison);
/// A repair's result: what was done (floor, clipped eigenvalues, iterations) and the matrix.
std::string report(const NearestResult& result);

}  // namespace spdfit
