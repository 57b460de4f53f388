// A hexapod identification rendered once for every front-end: the JSON of `spdfit hexapod
// identify --json` (and of Python's pickles) and its report for people.
#pragma once

#include <string>
#include <vector>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/physical.hpp"
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

/// The physical estimate as the identify document's `physical` object: physical_json's keys, and
/// error_vs_truth (||M_p(theta) - truth||_F) when options.truth is given. Cost O(1).
std::string to_json(const PhysicalEstimate& estimate, const IdentifyOptions& options);

/// `spdfit hexapod identify --physical --json`: the document of to_json(methods, options) with
/// the physical estimate under "physical" (to_json(estimate, options)). Cost O(methods n^2).
std::string to_json(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                    const PhysicalEstimate& physical);

/// The physical estimate for people: the payload's mass, centre of mass, inertia about it,
/// principal moments and axes and the strut masses, each beside the geometry's nominal value
/// (and with a bootstrap its standard error and interval); M_p(theta) (beside options.truth and
/// with its error when given), its eigenvalues and modes (with their intervals), the certificate
/// of the minimum found and the design's rank and condition. Cost O(1).
std::string report(const PhysicalEstimate& estimate, const Geometry& geometry,
                   const IdentifyOptions& options = {});

/// `spdfit hexapod identify --physical`: report(methods, options), then the physical estimate
/// (report(physical, geometry, options)) and, with a truth, which estimate is closest to it,
/// the physical one included. Cost O(methods n^2).
std::string report(const std::vector<MethodIdentification>& methods, const IdentifyOptions& options,
                   const PhysicalEstimate& physical, const Geometry& geometry);

}  // namespace spdfit::hexapod

namespace spdfit {

/// The entry that hexapod::to_json(const MethodIdentification&) wrote (see from_json).
template <> hexapod::MethodIdentification from_json<hexapod::MethodIdentification>(const std::string& text);
/// What hexapod::physical_json wrote (the "physical" object of `hexapod identify --json`).
template <> hexapod::PhysicalEstimate from_json<hexapod::PhysicalEstimate>(const std::string& text);

}  // namespace spdfit
