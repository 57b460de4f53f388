// The nearest physically consistent rigid-body inertia: a CAD or URDF inertia whose principal
// moments break the triangle inequality, repaired in closed form (`spdfit inertia repair`).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "spdfit/options.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit {

/// Which distance repair_inertia minimizes.
enum class InertiaMetric {
  /// ||I' - I_c||_F, the distance it reports (the inertia tensor's own entries).
  Inertia,
  /// ||Sigma' - Sigma_c||_F over the second moment Sigma_c = (1/2) tr(I_c) 1 - I_c: the eigenvalue
  /// clip of Sigma_c (Higham 1988), spdfit's repair before the inertia metric was the default.
  SecondMoment,
};

/// "inertia" or "second-moment".
std::string_view to_string(InertiaMetric metric);
std::optional<InertiaMetric> parse_inertia_metric(std::string_view name);

/// Options of repair_inertia.
struct InertiaRepairOptions {
  InertiaMetric metric = InertiaMetric::Inertia;
  /// The relative floor of the repaired second moment's eigenvalues: sigma_i' >= min_eig_rel *
  /// max_i |sigma_i|, so that each principal moment is below the sum of the other two by at
  /// least 2 min_eig_rel times the body's largest second moment. The default 1e-6 keeps that
  /// margin through rounding to 7 significant digits (the strict triangle checks of simulators
  /// and URDF parsers pass on the printed numbers) while moving the inertia by a negligible
  /// amount. A finite number in [0, 1); 0 gives the plain projection onto the semidefinite cone.
  double min_eig_rel = 1e-6;

  /// True when usable; otherwise `error` says why, naming `min_eig_rel`.
  bool is_valid(std::string* error = nullptr) const;
};

/// The optimality conditions of the projection min d(Sigma', Sigma_c) over Sigma' >= floor 1:
/// Sigma' is the minimizer exactly when primal_min_eig >= 0, dual_min_eig >= 0 and
/// complementarity = 0. The dual variable is the gradient of d^2 / 2: Z = Sigma' - Sigma_c for the
/// second-moment metric, Z = T(T(Sigma' - Sigma_c)) = tr(I' - I_c) 1 - (I' - I_c) for the inertia
/// metric (T(S) = tr(S) 1 - S, so that I = T(Sigma)). Computed from the returned inertia itself,
/// in its units (kg m^2; complementarity kg^2 m^4).
struct InertiaRepairCertificate {
  double primal_min_eig = 0.0;   ///< lambda_min(Sigma' - floor 1)
  double dual_min_eig = 0.0;     ///< lambda_min(Sigma' - Sigma_c)
  double complementarity = 0.0;  ///< <Sigma' - floor 1, Sigma' - Sigma_c>
};

/// What repair_inertia returns.
struct InertiaRepairResult {
  RigidBodyInertia input;     ///< as given
  RigidBodyInertia repaired;  ///< mass and centre of mass kept; the inertia repaired (or the input's, unchanged)
  bool changed = false;       ///< false: the input already met the floor and comes back bit for bit
  double distance = 0.0;      ///< ||I' - I_c||_F (kg m^2)
  double floor = 0.0;         ///< the floor applied to the second moment's eigenvalues (kg m^2)
  Eigen::Vector3d principal_moments_before = Eigen::Vector3d::Zero();  ///< of the input, ascending
  Eigen::Vector3d principal_moments = Eigen::Vector3d::Zero();         ///< of the result, ascending
  /// Eigenvalues of the input's second moment Sigma_c, ascending: a negative one is a broken
  /// triangle inequality (by twice its size).
  Eigen::Vector3d second_moments_before = Eigen::Vector3d::Zero();
  InertiaRepairCertificate certificate;
  InertiaMetric metric = InertiaMetric::Inertia;
  /// For the user to know: a principal moment changed by more than 10 % (the input may hold a
  /// typo: a misplaced digit, a product of inertia with the wrong sign), or a body with mass and an
  /// all-zero inertia (a placeholder, not a measured value).
  std::vector<Warning> warnings;
};

/// The nearest physically consistent inertia with the same mass and centre of mass. The second
/// moment about the centre of mass Sigma_c = (1/2) tr(I_c) 1 - I_c = V diag(sigma) V^T must have
/// eigenvalues >= floor = options.min_eig_rel max_i |sigma_i| (the triangle inequalities with a
/// margin). With the default metric (InertiaMetric::Inertia) the repair minimizes ||I' - I_c||_F,
/// the distance it reports: a projection onto a convex cone whose minimizer shares V (the problem
/// is invariant under the reflections that fix Sigma_c), found as the three-variable QP
/// min ||T(delta)||^2 over sigma + delta >= floor (T(delta)_i = sum(delta) - delta_i) by its eight
/// active sets and certified by its KKT conditions; about 20 % closer than the clip on typical
/// inputs (it also lowers the other second moments). InertiaMetric::SecondMoment is the clip
/// V diag(max(sigma_i, floor)) V^T (Higham 1988), the nearest in ||Sigma' - Sigma_c||_F and so
/// the nearest consistent pseudo-inertia for a fixed centre of mass and mass. I' = tr(Sigma') 1 -
/// Sigma'. An input whose sigma_i are all >= floor is returned unchanged (changed = false,
/// distance 0). The repair commutes with rotations, so the inertia may be given in any axes (a
/// URDF inertial frame's).
///
/// Preconditions: is_well_formed(body) and options.is_valid() (else std::invalid_argument with
/// the message, naming the field). Cost O(1) (one 3 x 3 eigendecomposition).
InertiaRepairResult repair_inertia(const RigidBodyInertia& body, const InertiaRepairOptions& options = {});

/// Reads a body from JSON text: {"mass": m, "center_of_mass": [x, y, z], "inertia": [[3x3]]}
/// (SI units, the inertia about the centre of mass). Keys starting with '_' are ignored, and so
/// are the keys inertia_repair_json adds (its output reads back); any other unknown key, a missing
/// key, a value of the wrong shape or type, or a body that is not well formed (is_well_formed) is
/// an io::DataError naming `source` and the key (with line and column for malformed JSON). The
/// JSON of `spdfit hexapod identify --physical --json` reads as its "physical" object, and that of
/// `spdfit payload identify --json` as its mass, center_of_mass and inertia (other keys ignored;
/// a null inertia, which static poses leave, is an error that says so).
RigidBodyInertia parse_rigid_body(const std::string& text, const std::string& source);

/// parse_rigid_body on the file at `path` (at most 1 MiB; io::DataError naming it otherwise, or
/// when it is not a readable regular file).
RigidBodyInertia read_rigid_body(const std::string& path);

/// Bodies from JSON text: a list of bodies as parse_rigid_body reads one, or {"bodies": [...]}
/// (a prior of `spdfit physical regress`). io::DataError naming `source` and the body's index.
std::vector<RigidBodyInertia> parse_rigid_bodies(const std::string& text, const std::string& source);
std::vector<RigidBodyInertia> read_rigid_bodies(const std::string& path);

/// The result as JSON text: {"mass", "center_of_mass", "inertia", "changed", "distance",
/// "certificate": {"primal_min_eig", "dual_min_eig", "complementarity"}, "min_eig" (the floor),
/// "principal_moments", "principal_moments_before", "second_moments_before", "metric",
/// "warnings"}. The first three
/// are the repaired body, in the input format, so the output can be read back by
/// parse_rigid_body; numbers round-trip exactly.
std::string inertia_repair_json(const InertiaRepairResult& result);

/// One URDF link's <inertial> as checked.
struct UrdfLinkRepair {
  std::string link;       ///< the link's name attribute
  std::size_t line = 0;   ///< the line of its <inertia> element
  InertiaRepairResult result;
};

/// What repair_urdf returns.
struct UrdfRepairResult {
  std::string text;                    ///< the URDF with the repaired inertias, otherwise unchanged byte for byte
  std::vector<UrdfLinkRepair> links;   ///< every link with an <inertial>, in document order
  /// How many links were repaired.
  std::size_t changed() const;
};

/// Checks every <link>'s <inertial> of a URDF document and repairs (repair_inertia) those that are
/// not consistent: those of the six attributes ixx, ixy, ixz, iyy, iyz, izz of a repaired link's
/// <inertia> element whose value the repair changed get the repaired values (the shortest text
/// that reads back exactly); every other byte of the document, comments, formatting, the other
/// attributes and elements included, is kept. The inertia is
/// taken in the inertial frame's axes (its <origin rpy>, kept), the centre of mass is <origin xyz>
/// (default 0 0 0), the mass <mass value>. Links without <inertial> are left alone.
///
/// Errors (io::DataError naming `source`, the line and the link): XML that does not parse, a root
/// that is not <robot>, an <inertial> without <mass> or <inertia>, a missing or non-numeric
/// attribute, a mass that is not positive, an invalid `options` (std::invalid_argument).
/// Cost O(size of the document).
UrdfRepairResult repair_urdf(const std::string& text, const std::string& source,
                             const InertiaRepairOptions& options = {});

/// What repair_urdf did, for people: one line per link with an <inertial> (consistent, or repaired
/// with its principal moments before and after and how far the inertia moved), then "K of N links
/// repaired".
std::string urdf_repair_report(const UrdfRepairResult& result);

/// A body as a URDF <link name="NAME"> with its <inertial>: <origin xyz> the centre of mass (rpy
/// 0 0 0: the inertia in the body frame's axes), <mass value>, <inertia ixx ... izz> about the
/// centre of mass, each number to `precision` significant digits (1 to 17); the name XML-escaped.
/// std::invalid_argument when the body is not well formed (is_well_formed: a mass <= 0, a
/// non-finite entry, an inertia not symmetric) or the precision is out of range. What `spdfit
/// hexapod identify --physical --urdf` and `spdfit payload identify --urdf` write; repair_urdf
/// reads it back.
std::string urdf_link(const RigidBodyInertia& body, const std::string& name, int precision = 9);

/// repair_urdf on the file at `path` (at most 64 MiB).
UrdfRepairResult repair_urdf_file(const std::string& path, const InertiaRepairOptions& options = {});

/// `spdfit inertia repair`'s request: the file (a JSON body, or a URDF file: .urdf or .xml in any
/// case), the repair's options and where the result goes.
struct InertiaRepairRequest {
  std::string input;
  InertiaRepairOptions options;
  OutputRequest output;  ///< `output` only (the JSON body, or the URDF; a URDF's report is separate)
};

/// The options of `inertia repair` (and of Python's spdfit.physical.inertia_repair and
/// inertia_repair_urdf): the file, min_eig_rel, metric, output.
const std::vector<OptionSpec<InertiaRepairRequest>>& inertia_repair_option_table();

/// Whether `path` names a URDF file (.urdf or .xml, any case); anything else is a JSON body.
bool is_urdf_path(std::string_view path);

/// What `inertia repair` returns: one body's repair, or every link of a URDF file.
struct InertiaRepairRun {
  std::optional<InertiaRepairResult> body;
  std::optional<UrdfRepairResult> urdf;
};

/// The workflow of `inertia repair`: the request's file read and repaired (io::DataError naming
/// the file for one that is not a body or a URDF document).
InertiaRepairRun run_inertia_repair(const InertiaRepairRequest& request);

/// What inertia_repair_json wrote, read back (spdfit/render.hpp's from_json): every key it writes;
/// std::invalid_argument naming the class and the key for another document.
template <typename T>
T from_json(const std::string& text);
template <> InertiaRepairResult from_json<InertiaRepairResult>(const std::string& text);

}  // namespace spdfit
