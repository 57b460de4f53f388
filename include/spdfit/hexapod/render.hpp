// A hexapod identification rendered once for every front-end: the JSON of `spdfit hexapod
// identify --json` (and of Python's pickles) and its report for people.
#pragma once

#include <string>
#include <vector>

#include "spdfit/hexapod/identify.hpp"
#include "spdfit/render.hpp"

namespace spdfit::hexapod {

/// One method's entry of the identify document: its FitResult's JSON (to_json(FitResult)) with
/// eigenvalues, modes_hz and error_vs_truth when present, and the modes' bootstrap intervals as
/// bootstrap.modes_hz. Cost O(n^2).
std::string to_json(const MethodIdentification& method, JsonStyle style = JsonStyle::Contract);

/// `spdfit hexapod identify --json`: m, n, the truth (when given), the stiffness (null when not
/// given) and "methods", each method's entry under its name. Cost O(methods n^2).
std::string to_json(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                    JsonStyle style = JsonStyle::Contract);

/// `spdfit hexapod identify`: the data, the estimates side by side (with the truth), a table of
/// their diagnostics and errors, their eigenvalues and modes, the bootstrap's intervals (with
/// options.fit.bootstrap > 0) and the estimate closest to the truth. Cost O(methods n^2).
std::string report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options);

}  // namespace spdfit::hexapod

namespace spdfit {

/// The entry that hexapod::to_json(const MethodIdentification&) wrote (see from_json).
template <> hexapod::MethodIdentification from_json<hexapod::MethodIdentification>(const std::string& text);

}  // namespace spdfit
