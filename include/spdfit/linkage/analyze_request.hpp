// `spdfit linkage analyze`: the request (a four-bar's lengths, the input angles), its option table,
// the workflow and its renderings. Python's spdfit.linkage.analyze calls linkage::analyze on its
// own input angles (an array; its defaults are -180:180 in 361 angles).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "spdfit/linkage/analysis.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"

namespace spdfit::linkage {

/// What `linkage analyze` analyzes.
struct AnalyzeRequest {
  std::vector<double> lengths;     ///< a1, a2, a3, a4: ground, input, coupler, output
  std::string psi_range = "0:360";  ///< the input angles LO:HI, degrees
  int points = 37;                 ///< the number of input angles, evenly spaced over psi_range
  /// The input angles themselves (radians), instead of psi_range and points: Python's psi.
  Eigen::VectorXd psi;
  OutputRequest output;            ///< `json` and `output`
};

/// The options of `linkage analyze`.
const std::vector<OptionSpec<AnalyzeRequest>>& analyze_option_table();

/// The workflow of `linkage analyze`: the request checked (four positive lengths, LO < HI, at
/// least 2 points, finite input angles, not both the angles and psi_range or points: OptionError
/// naming the option) and the four-bar analyzed at the input angles. `given`: the library names
/// of the options given.
Analysis run_analyze(const AnalyzeRequest& request, const std::vector<std::string_view>& given = {});

/// The analysis as the command line's JSON document (angles in degrees) and its report.
std::string to_json(const Analysis& analysis);
std::string report(const Analysis& analysis);

}  // namespace spdfit::linkage
