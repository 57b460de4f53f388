// `payload identify`'s options declared once (identify_option_table), their rules
// (IdentifyRequest::is_valid), and the identification from a log file's columns.
#include <cmath>
#include <string>

#include "payload/kinematics.hpp"
#include "physical/common_options.hpp"
#include "spdfit/payload/identify.hpp"

namespace spdfit::payload {

namespace {

using Spec = OptionSpec<IdentifyRequest>;
using physical::detail::choice_option;
using physical::detail::columns_option;
using physical::detail::flag_option;
using physical::detail::text_option;

std::optional<OptionValue> list_value(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  return v;
}

std::vector<Spec> make_table() {
  std::vector<Spec> table;
  Spec log = text_option<IdentifyRequest>("log", "LOG", "", "",
                                          "The log: one table (any format spdfit reads), columns chosen by the "
                                          "`*_cols` options",
                                          "");
  log.type = OptionType::File;
  log.positional = true;
  log.required = true;
  log.set = [](IdentifyRequest& r, const OptionValue& v) { r.log = std::get<std::string>(v); };
  table.push_back(log);
  const auto add_columns = [&table](std::string_view name, std::string_view cli, std::string_view help,
                                    void (*set)(IdentifyRequest&, const OptionValue&)) {
    Spec spec = columns_option<IdentifyRequest>(name, cli, name, name == "time_col" ? "COL" : "COLS", help);
    spec.set = set;
    table.push_back(spec);
  };
  add_columns("wrench_cols", "--wrench-cols",
              "The wrench's 6 columns (fx fy fz tx ty tz; N and N m): header names or 1-based positions, ranges and "
              "lists, as `a_cols` takes them ('fx:tz', '2:7')",
              [](IdentifyRequest& r, const OptionValue& v) { r.wrench_cols = std::get<std::string>(v); });
  add_columns("quat_cols", "--quat-cols",
              "The orientation as a quaternion's 4 columns (the rotation from the sensor frame to the world, x y z w "
              "as ROS writes it; `quat_order` wxyz for w first)",
              [](IdentifyRequest& r, const OptionValue& v) { r.quat_cols = std::get<std::string>(v); });
  Spec order = choice_option<IdentifyRequest>("quat_order", "--quat-order", "quat_order", {"xyzw", "wxyz"},
                                              "The quaternion columns' order", "xyzw");
  order.set = [](IdentifyRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_quaternion_order(name);
    if (!parsed) throw OptionError("`quat_order` must be xyzw or wxyz, got '" + name + "'");
    r.quat_order = *parsed;
  };
  order.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.quat_order)); };
  table.push_back(order);
  add_columns("rotation_cols", "--rotation-cols",
              "The orientation as the rotation matrix's 9 columns, row-major (R maps the sensor frame to the world)",
              [](IdentifyRequest& r, const OptionValue& v) { r.rotation_cols = std::get<std::string>(v); });
  add_columns("gravity_cols", "--gravity-cols",
              "The orientation as gravity's 3 columns in the sensor frame (m/s^2; about -9.81 along the axis that "
              "points up)",
              [](IdentifyRequest& r, const OptionValue& v) { r.gravity_cols = std::get<std::string>(v); });
  add_columns("accel_cols", "--accel-cols",
              "The sensor origin's kinematic acceleration, 3 columns in the sensor frame (m/s^2, zero at rest)",
              [](IdentifyRequest& r, const OptionValue& v) { r.accel_cols = std::get<std::string>(v); });
  add_columns("specific_force_cols", "--specific-force-cols",
              "An IMU's specific force instead, a - R^T g (3 columns, +9.81 m/s^2 upwards at rest): gravity is in it, "
              "so no orientation is needed",
              [](IdentifyRequest& r, const OptionValue& v) { r.specific_force_cols = std::get<std::string>(v); });
  add_columns("omega_cols", "--omega-cols",
              "The angular velocity's 3 columns in the sensor frame (rad/s): the inertia enters the model",
              [](IdentifyRequest& r, const OptionValue& v) { r.omega_cols = std::get<std::string>(v); });
  add_columns("alpha_cols", "--alpha-cols",
              "The angular acceleration's 3 columns (rad/s^2); without them, omega's central differences in "
              "`time_col`",
              [](IdentifyRequest& r, const OptionValue& v) { r.alpha_cols = std::get<std::string>(v); });
  add_columns("time_col", "--time-col",
              "The time column (s): alpha from omega, and `rows` and `rest_rows` as ranges of time",
              [](IdentifyRequest& r, const OptionValue& v) { r.time_col = std::get<std::string>(v); });
  Spec rows = text_option<IdentifyRequest>("rows", "--rows", "rows", "SPEC",
                                           "The rows fitted: 1-based inclusive ranges and lists ('601:', "
                                           "'1:5000,7001:'), in the time column's units with `time_col`",
                                           "all");
  rows.type = OptionType::Rows;
  rows.set = [](IdentifyRequest& r, const OptionValue& v) { r.rows = std::get<std::string>(v); };
  table.push_back(rows);
  Spec rest = text_option<IdentifyRequest>("rest_rows", "--rest-rows", "rest_rows", "SPEC",
                                           "Rows recorded at rest (as `rows`): the noise model's covariances of the "
                                           "wrench and the pose signals are their sample covariances",
                                           "");
  rest.type = OptionType::Rows;
  rest.set = [](IdentifyRequest& r, const OptionValue& v) { r.rest_rows = std::get<std::string>(v); };
  table.push_back(rest);

  Spec sign = choice_option<IdentifyRequest>(
      "wrench_sign", "--wrench-sign", "wrench_sign", {"load", "applied"},
      "What the readings are: the load the payload applies to the sensor (what sensors report: a payload at rest "
      "reads a downward force) or the wrench applied to the payload",
      "load");
  sign.set = [](IdentifyRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_wrench_sign(name);
    if (!parsed) throw OptionError("`wrench_sign` must be load or applied, got '" + name + "'");
    r.wrench_sign = *parsed;
  };
  sign.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.wrench_sign)); };
  table.push_back(sign);
  Spec frame = choice_option<IdentifyRequest>(
      "frame", "--frame", "frame", {"sensor", "base"},
      "The wrench's axes as logged: the sensor frame's, or the base frame's (rotated by the logger; the torque still "
      "about the sensor's origin)",
      "sensor");
  frame.set = [](IdentifyRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_wrench_frame(name);
    if (!parsed) throw OptionError("`frame` must be sensor or base, got '" + name + "'");
    r.frame = *parsed;
  };
  frame.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.frame)); };
  table.push_back(frame);
  Spec gravity;
  gravity.name = "gravity";
  gravity.cli = "--gravity";
  gravity.python = "gravity";
  gravity.type = OptionType::RealList;
  gravity.value_name = "X,Y,Z";
  gravity.help = "Gravity in the world frame (m/s^2)";
  gravity.default_text = "0,0,-9.80665";
  gravity.excludes = {"gravity_cols"};
  gravity.set = [](IdentifyRequest& r, const OptionValue& v) {
    const auto& g = std::get<std::vector<double>>(v);
    if (g.size() != 3) throw OptionError("`gravity` must be 3 numbers (x, y, z in the world frame, m/s^2)");
    r.gravity = Eigen::Vector3d(g[0], g[1], g[2]);
  };
  table.push_back(gravity);

  Spec criterion = choice_option<IdentifyRequest>(
      "criterion", "--criterion", "criterion", {"ls", "eiv"},
      "Least squares (noise in the wrench only) or errors in variables (noise in the pose signals too, weighed by "
      "the noise model: `noise_std_*` or `rest_rows`)",
      "ls");
  criterion.set = [](IdentifyRequest& r, const OptionValue& v) {
    const std::string& name = std::get<std::string>(v);
    const auto parsed = parse_criterion(name);
    if (!parsed) throw OptionError("`criterion` must be ls or eiv, got '" + name + "'");
    r.criterion = *parsed;
  };
  criterion.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> {
    return std::string(to_string(r.criterion));
  };
  table.push_back(criterion);

  Spec consistent;
  consistent.name = "consistent";
  consistent.python = "consistent";
  consistent.type = OptionType::Boolean;
  consistent.help = "Enforce physical consistency (the pseudo-inertia positive semidefinite; m >= 0 for static "
                    "poses); False is the unconstrained fit";
  consistent.default_text = "True";
  consistent.nullable = false;
  consistent.excludes = {"unconstrained"};
  consistent.set = [](IdentifyRequest& r, const OptionValue& v) { r.consistent = std::get<bool>(v); };
  consistent.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return r.consistent; };
  table.push_back(consistent);
  Spec unconstrained = flag_option<IdentifyRequest>(
      "unconstrained", "--unconstrained", "",
      "The fit without the consistency constraint, for comparison (it may return a payload that cannot exist)");
  unconstrained.excludes = {"consistent"};
  unconstrained.set = [](IdentifyRequest& r, const OptionValue& v) {
    if (std::get<bool>(v)) r.consistent = false;
  };
  table.push_back(unconstrained);

  const auto add_std = [&table](std::string_view name, std::string_view cli, std::string_view help,
                                void (*set)(IdentifyRequest&, const OptionValue&),
                                std::optional<OptionValue> (*get)(const IdentifyRequest&), bool positive) {
    Spec spec;
    spec.name = name;
    spec.cli = cli;
    spec.python = name;
    spec.type = OptionType::RealList;
    spec.value_name = "S";
    spec.help = help;
    spec.range = {0.0, std::numeric_limits<double>::infinity(), positive, false};
    spec.excludes = {"rest_rows"};
    spec.set = set;
    spec.get = get;
    table.push_back(spec);
  };
  add_std("noise_std_wrench", "--noise-std-wrench",
          "Standard deviation of the wrench's noise: one for all six axes, two (force N, torque N m) or six; weights "
          "the least-squares fit",
          [](IdentifyRequest& r, const OptionValue& v) { r.noise_std_wrench = std::get<std::vector<double>>(v); },
          [](const IdentifyRequest& r) { return list_value(r.noise_std_wrench); }, true);
  add_std("noise_std_accel", "--noise-std-accel",
          "Standard deviation of the noise in the linear acceleration signal (the acceleration, the specific force, "
          "or gravity in the sensor frame; m/s^2): one or three",
          [](IdentifyRequest& r, const OptionValue& v) { r.noise_std_accel = std::get<std::vector<double>>(v); },
          [](const IdentifyRequest& r) { return list_value(r.noise_std_accel); }, false);
  add_std("noise_std_omega", "--noise-std-omega", "Standard deviation of the noise in omega (rad/s): one or three",
          [](IdentifyRequest& r, const OptionValue& v) { r.noise_std_omega = std::get<std::vector<double>>(v); },
          [](const IdentifyRequest& r) { return list_value(r.noise_std_omega); }, false);
  add_std("noise_std_alpha", "--noise-std-alpha",
          "Standard deviation of the noise in alpha (rad/s^2): one or three (default for alpha from omega: omega's "
          "divided by sqrt(2) dt)",
          [](IdentifyRequest& r, const OptionValue& v) { r.noise_std_alpha = std::get<std::vector<double>>(v); },
          [](const IdentifyRequest& r) { return list_value(r.noise_std_alpha); }, false);

  // fit's robust options, spelled and checked as fit's table does, setting the payload fit's.
  Spec robust = physical::detail::like_fit_option<IdentifyRequest>("robust");
  robust.help = "A robust fit: samples reweighted by their residual wrench, whitened by the criterion's covariance "
                "(the wrench noise's, or each axis' robust scale without one), each reweighting the criterion's "
                "fit of the weighted samples (an M-estimator); huber for gross errors in some samples, tukey "
                "(from huber's fit) to give the worst weight 0. With `bootstrap`, each resample is reweighted";
  robust.set = [](IdentifyRequest& r, const OptionValue& v) {
    r.robust = robust_loss_named(std::get<std::string>(v)).value_or(RobustLoss::None);  // a choice: named
  };
  robust.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::string(to_string(r.robust)); };
  table.push_back(robust);
  Spec tuning = physical::detail::like_fit_option<IdentifyRequest>("robust_tuning");
  tuning.help = "The robust loss's constant, in standard deviations of a sample's whitened residual norm (default: "
                "95% of least squares' efficiency at Gaussian noise on the six axes: Huber 1.869, Tukey 6.356)";
  tuning.set = [](IdentifyRequest& r, const OptionValue& v) { r.robust_tuning = std::get<double>(v); };
  tuning.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> {
    if (!r.robust_tuning) return std::nullopt;
    return *r.robust_tuning;
  };
  table.push_back(tuning);

  physical::detail::add_solver_options(table, "500");
  physical::detail::add_bootstrap_options(
      table, "Resample the samples N times for percentile intervals and bootstrap standard errors of the mass, "
             "centre of mass, inertia and biases (each replicate refitted)");

  Spec urdf = text_option<IdentifyRequest>("urdf", "--urdf", "", "FILE",
                                           "Also write the payload as a URDF <link> with its <inertial> to FILE "
                                           "(moving poses: the inertia is needed)",
                                           "");
  urdf.type = OptionType::File;
  urdf.set = [](IdentifyRequest& r, const OptionValue& v) { r.urdf = std::get<std::string>(v); };
  table.push_back(urdf);
  Spec link = text_option<IdentifyRequest>("link_name", "--link-name", "", "NAME", "The URDF link's name", "payload");
  link.needs = {"urdf"};
  link.set = [](IdentifyRequest& r, const OptionValue& v) { r.link_name = std::get<std::string>(v); };
  table.push_back(link);
  Spec precision;
  precision.name = "precision";
  precision.cli = "--precision";
  precision.type = OptionType::Integer;
  precision.value_name = "N";
  precision.help = "Significant digits of the URDF's numbers";
  precision.default_text = "9";
  precision.range = {1.0, 17.0};
  precision.needs = {"urdf"};
  precision.set = [](IdentifyRequest& r, const OptionValue& v) { r.precision = int(std::get<std::int64_t>(v)); };
  precision.get = [](const IdentifyRequest& r) -> std::optional<OptionValue> { return std::int64_t{r.precision}; };
  table.push_back(precision);
  for (Spec& spec : output_options(&IdentifyRequest::output, {"json", "output"}, {"Print the estimate as JSON"})) {
    table.push_back(std::move(spec));
  }
  return table;
}

}  // namespace

const std::vector<OptionSpec<IdentifyRequest>>& identify_option_table() {
  static const std::vector<OptionSpec<IdentifyRequest>> table = make_table();
  return table;
}

bool IdentifyRequest::is_valid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!options_in_range(*this, identify_option_table(), error)) return false;
  if (!gravity.allFinite() || !(gravity.norm() > 0.0)) return fail("`gravity` must be a finite, nonzero vector");
  for (double s : noise_std_wrench)
    if (!(s > 0.0)) return fail("`noise_std_wrench` must be > 0 (every axis has some noise)");
  if (!noise_std_wrench.empty() && noise_std_wrench.size() != 1 && noise_std_wrench.size() != 2 &&
      noise_std_wrench.size() != 6) {
    return fail("`noise_std_wrench` takes 1, 2 (force, torque) or 6 standard deviations, not " +
                std::to_string(noise_std_wrench.size()));
  }
  for (const auto* list : {&noise_std_accel, &noise_std_omega, &noise_std_alpha}) {
    if (!list->empty() && list->size() != 1 && list->size() != 3) {
      const char* name = list == &noise_std_accel ? "noise_std_accel" : list == &noise_std_omega ? "noise_std_omega"
                                                                                                  : "noise_std_alpha";
      return fail("`" + std::string(name) + "` takes 1 or 3 standard deviations, not " + std::to_string(list->size()));
    }
  }
  const bool stds = !noise_std_wrench.empty() || !noise_std_accel.empty() || !noise_std_omega.empty() ||
                    !noise_std_alpha.empty();
  if (stds && !rest_rows.empty()) return fail("give the noise as `noise_std_*` or as `rest_rows`, not both");
  return true;
}

void check_identify_request(const IdentifyRequest& /*request*/, const std::vector<std::string_view>& given) {
  check_option_combination(identify_option_table(), given);
}

PayloadEstimate run_identify(const IdentifyRequest& request) { return identify_file(request.log, request); }

PayloadEstimate identify_file(const std::string& path, const IdentifyRequest& request) {
  std::string error;
  if (!request.is_valid(&error)) throw OptionError(error);
  if (request.wrench_cols.empty()) throw OptionError("`wrench_cols` is needed: the wrench's 6 columns in the log", Code::Argument);
  struct Selected {
    const std::string* spec;
    const char* option;
    Eigen::Index columns;
    const char* what;
    Eigen::MatrixXd PayloadSignals::*matrix;
  };
  const Selected selections[] = {
      {&request.wrench_cols, "wrench_cols", 6, "the wrench (fx fy fz tx ty tz)", &PayloadSignals::wrench},
      {&request.quat_cols, "quat_cols", 4, "a quaternion", &PayloadSignals::quaternion},
      {&request.rotation_cols, "rotation_cols", 9, "a rotation matrix, row-major", &PayloadSignals::rotation},
      {&request.gravity_cols, "gravity_cols", 3, "gravity in the sensor frame", &PayloadSignals::gravity},
      {&request.accel_cols, "accel_cols", 3, "the acceleration", &PayloadSignals::accel},
      {&request.specific_force_cols, "specific_force_cols", 3, "the specific force", &PayloadSignals::specific_force},
      {&request.omega_cols, "omega_cols", 3, "omega", &PayloadSignals::omega},
      {&request.alpha_cols, "alpha_cols", 3, "alpha", &PayloadSignals::alpha},
  };
  io::ReadOptions read = request.read;
  read.columns.clear();
  std::vector<const Selected*> used;
  for (const Selected& s : selections) {
    if (s.spec->empty()) continue;
    read.columns.push_back({*s.spec, s.option});
    used.push_back(&s);
  }
  if (!request.time_col.empty()) read.columns.push_back({request.time_col, "time_col"});
  for (const io::ColumnSelection& c : read.columns) io::check_column_selection(c);
  const io::Table table = io::read_table(path, read);
  PayloadSignals signals;
  Eigen::Index at = 0;
  for (std::size_t k = 0; k < used.size(); ++k) {
    const Eigen::Index n = static_cast<Eigen::Index>(table.selected_columns[k].size());
    if (n != used[k]->columns) {
      throw io::ColumnSelectionError("`" + std::string(used[k]->option) + "` = '" + *used[k]->spec + "' selects " +
                                     std::to_string(n) + (n == 1 ? " column" : " columns") + " of " + path + ": " +
                                     used[k]->what + " needs " + std::to_string(used[k]->columns));
    }
    signals.*(used[k]->matrix) = table.values.middleCols(at, n);
    at += n;
  }
  if (!request.time_col.empty()) {
    const std::size_t k = used.size();
    if (table.selected_columns[k].size() != 1) {
      throw io::ColumnSelectionError("`time_col` = '" + request.time_col + "' selects " +
                                     std::to_string(table.selected_columns[k].size()) + " columns of " + path +
                                     ": give one");
    }
    signals.time = table.values.col(at);
  }
  try {
    PayloadEstimate out = identify(signals, request);
    out.warnings.insert(out.warnings.begin(), table.warnings.begin(), table.warnings.end());
    return out;
  } catch (const detail::SignalError& e) {
    throw io::DataError(path, 0, 0, e.what(), e.code());
  }
}

}  // namespace spdfit::payload
