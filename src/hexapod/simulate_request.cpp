// `hexapod simulate`'s option table, workflow and files.
#include <filesystem>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "interface/option_builders.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/hexapod/simulation_warnings.hpp"

namespace spdfit::hexapod {

namespace {

using SimulateSpec = OptionSpec<SimulateRequest>;

SimulateSpec simulate_option(std::string_view name, std::string_view cli, OptionType type, std::string_view value_name,
                             std::string_view help, std::string_view default_text = {}) {
  return spdfit::detail::option_entry<SimulateRequest>(name, cli, name, type, value_name, help, default_text);
}

Eigen::VectorXd vector_of(const OptionValue& v) {
  const std::vector<double>& values = std::get<std::vector<double>>(v);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), Eigen::Index(values.size()));
}

std::vector<SimulateSpec> make_simulate_table() {
  std::vector<SimulateSpec> table;
  SimulateSpec samples = simulate_option("samples", "--samples", OptionType::Integer, "M", "Samples m (rows of A and B)",
                                         "12");
  samples.range = {1.0, 1e8};
  samples.nullable = false;
  samples.set = [](SimulateRequest& r, const OptionValue& v) { r.options.samples = Eigen::Index(std::get<std::int64_t>(v)); };
  samples.get = [](const SimulateRequest& r) -> std::optional<OptionValue> { return std::int64_t(r.options.samples); };
  table.push_back(samples);

  SimulateSpec noise = simulate_option("noise_var", "--noise-var", OptionType::Real, "V",
                                       "Variance V of the noise in every entry of A and B (or `noise_std_a` and "
                                       "`noise_std_b`)");
  noise.range = {0.0, std::numeric_limits<double>::infinity()};
  noise.set = [](SimulateRequest& r, const OptionValue& v) {
    r.options.noise_var = std::get<double>(v);
    r.noise_given = true;
  };
  table.push_back(noise);

  SimulateSpec force = simulate_option("force_noise_var", "--force-noise-var", OptionType::Real, "V",
                                       "Variance of the noise in B when it differs from A's (default: `noise_var`, "
                                       "as the thesis)");
  force.range = {0.0, std::numeric_limits<double>::infinity()};
  force.set = [](SimulateRequest& r, const OptionValue& v) { r.options.force_noise_var = std::get<double>(v); };
  table.push_back(force);

  SimulateSpec signal = simulate_option("signal_var", "--signal-var", OptionType::Real, "S",
                                        "Variance S of the true accelerations, uniform on [-sqrt(3 S), sqrt(3 S)]",
                                        "25/3: [-5, 5]");
  signal.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  signal.set = [](SimulateRequest& r, const OptionValue& v) { r.options.signal_var = std::get<double>(v); };
  signal.get = [](const SimulateRequest& r) -> std::optional<OptionValue> { return r.options.signal_var; };
  table.push_back(signal);

  SimulateSpec distribution = simulate_option("distribution", "--distribution", OptionType::Choice, "",
                                              "Noise distribution: uniform (the thesis') or gaussian", "uniform");
  distribution.choices = {"uniform", "gaussian"};
  distribution.nullable = false;
  distribution.set = [](SimulateRequest& r, const OptionValue& v) {
    r.options.distribution = *parse_noise_distribution(std::get<std::string>(v));
  };
  distribution.get = [](const SimulateRequest& r) -> std::optional<OptionValue> {
    return std::string(to_string(r.options.distribution));
  };
  table.push_back(distribution);

  SimulateSpec truth = simulate_option("truth", "--truth", OptionType::Matrix, "FILE",
                                       "True M_p: 'thesis' (eq. 6.1) or a matrix file (n x n)", "thesis");
  truth.set = [](SimulateRequest& r, const OptionValue& v) { r.truth = std::get<MatrixInput>(v); };
  table.push_back(truth);

  SimulateSpec geometry = simulate_option("geometry", "--geometry", OptionType::Geometry, "FILE",
                                          "Use the M_p of this geometry file as the truth");
  geometry.excludes = {"truth"};
  geometry.set = [](SimulateRequest& r, const OptionValue& v) { r.geometry = std::get<GeometryInput>(v); };
  table.push_back(geometry);

  const std::string_view payload_needs =
      "`payload_mass`, `payload_com` and `payload_inertia` change the payload of `geometry`: give it";
  SimulateSpec mass = simulate_option("payload_mass", "--payload-mass", OptionType::Real, "KG",
                                      "The true payload's mass (kg; default the geometry's)");
  mass.needs = {"geometry"};
  mass.needs_message = payload_needs;
  mass.set = [](SimulateRequest& r, const OptionValue& v) { r.payload.mass = std::get<double>(v); };
  table.push_back(mass);
  SimulateSpec com = simulate_option("payload_com", "--payload-com", OptionType::RealList, "X,Y,Z",
                                     "The true payload's centre of mass x,y,z (m, {P}'s axes, from "
                                     "{P}'s origin, the nominal centre of mass; default 0,0,0)");
  com.needs = {"geometry"};
  com.needs_message = payload_needs;
  com.set = [](SimulateRequest& r, const OptionValue& v) {
    r.payload.center_of_mass = std::get<std::vector<double>>(v);
  };
  table.push_back(com);
  SimulateSpec inertia = simulate_option(
      "payload_inertia", "--payload-inertia", OptionType::RealList, "I",
      "The true payload's inertia about its centre of mass ({P}'s axes, kg m^2): 3 numbers (the "
      "diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz as URDF orders them) or 9 (row by row); default the geometry's");
  inertia.needs = {"geometry"};
  inertia.needs_message = payload_needs;
  inertia.set = [](SimulateRequest& r, const OptionValue& v) { r.payload.inertia = std::get<std::vector<double>>(v); };
  table.push_back(inertia);

  SimulateSpec seed = simulate_option("seed", "--seed", OptionType::Integer, "N",
                                      "Seed; the data are those of trial 0 of 'spdfit experiment thesis' with the same "
                                      "seed and settings",
                                      "1");
  seed.range = {0.0, 9223372036854775807.0};
  seed.nullable = false;
  seed.set = [](SimulateRequest& r, const OptionValue& v) { r.seed = std::uint64_t(std::get<std::int64_t>(v)); };
  seed.get = [](const SimulateRequest& r) -> std::optional<OptionValue> { return std::int64_t(r.seed); };
  table.push_back(seed);

  SimulateSpec out = simulate_option("out", "--out", OptionType::File, "",
                                     "Directory to write A.csv, B.csv, truth.csv and simulation.json to (and "
                                     "rest_A.csv, rest_B.csv with `rest_samples`)");
  out.python = "";
  out.required = true;
  out.set = [](SimulateRequest& r, const OptionValue& v) { r.out = std::get<std::string>(v); };
  table.push_back(out);

  const std::string_view std_pair = "`noise_std_a` and `noise_std_b` come together: the noise of A and of B";
  SimulateSpec std_a = simulate_option("noise_std_a", "--noise-std-a", OptionType::RealList, "S",
                                       "Standard deviation of the noise in A: one for every column, or one per column "
                                       "(comma-separated); 0: exact. Instead of `noise_var`");
  std_a.range = {0.0, std::numeric_limits<double>::infinity()};
  std_a.needs = {"noise_std_b"};
  std_a.needs_message = std_pair;
  std_a.excludes = {"noise_var"};
  std_a.set = [](SimulateRequest& r, const OptionValue& v) {
    r.options.noise_std_a = vector_of(v);
    r.noise_given = true;
  };
  table.push_back(std_a);
  SimulateSpec std_b = simulate_option("noise_std_b", "--noise-std-b", OptionType::RealList, "S",
                                       "Standard deviation of the noise in B, as `noise_std_a` (in B's units before "
                                       "`scale_b`)");
  std_b.range = {0.0, std::numeric_limits<double>::infinity()};
  std_b.needs = {"noise_std_a"};
  std_b.needs_message = std_pair;
  std_b.excludes = {"force_noise_var"};
  std_b.set = [](SimulateRequest& r, const OptionValue& v) { r.options.noise_std_b = vector_of(v); };
  table.push_back(std_b);

  SimulateSpec rest = simulate_option("rest_samples", "--rest-samples", OptionType::Integer, "N",
                                      "Also N rows recorded at rest (accelerations zero, forces constant) with the "
                                      "same noise");
  rest.range = {0.0, 1e8};
  rest.nullable = false;
  rest.set = [](SimulateRequest& r, const OptionValue& v) { r.options.rest_samples = Eigen::Index(std::get<std::int64_t>(v)); };
  rest.get = [](const SimulateRequest& r) -> std::optional<OptionValue> { return std::int64_t(r.options.rest_samples); };
  table.push_back(rest);

  SimulateSpec scale = simulate_option("scale_b", "--scale-b", OptionType::Real, "F",
                                       "Multiply B (and the rest rows of B) by F after drawing: 0.001 gives forces in "
                                       "kN, the true X then M_p / 1000");
  scale.range = {0.0, std::numeric_limits<double>::infinity(), true, false};
  scale.nullable = false;
  scale.set = [](SimulateRequest& r, const OptionValue& v) { r.options.scale_b = std::get<double>(v); };
  scale.get = [](const SimulateRequest& r) -> std::optional<OptionValue> { return r.options.scale_b; };
  table.push_back(scale);

  SimulateSpec preload = simulate_option("preload", "--preload", OptionType::RealList, "F",
                                         "A static load in every row of B, moving or at rest (untared forces): one "
                                         "value for every strut, or one per strut (comma-separated), in B's units "
                                         "before `scale_b`. Default: none");
  preload.set = [](SimulateRequest& r, const OptionValue& v) { r.preload = std::get<std::vector<double>>(v); };
  table.push_back(preload);
  return table;
}

// An inertia about the centre of mass from 3 (the diagonal), 6 (URDF's order) or 9 numbers.
Eigen::Matrix3d inertia_of(const std::vector<double>& v) {
  Eigen::Matrix3d I;
  if (v.size() == 3) {
    I = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
  } else if (v.size() == 6) {
    I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  } else {
    I << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  }
  return I;
}

}  // namespace

const std::vector<OptionSpec<SimulateRequest>>& simulate_option_table() {
  static const std::vector<OptionSpec<SimulateRequest>> table = make_simulate_table();
  return table;
}

RigidBodyInertia payload_with(const Geometry& geometry, const PayloadChange& change) {
  const auto count = [](const char* option, std::size_t given, std::initializer_list<std::size_t> counts,
                        const std::string& expected) {
    for (std::size_t c : counts) {
      if (given == c) return;
    }
    throw OptionError("`" + std::string(option) + "`: give " + expected + ", not " + std::to_string(given) + " numbers",
                      Code::OptionValue, option);
  };
  // Each change checked as it is made, so that the error names the option that broke the body.
  RigidBodyInertia body = nominal_payload(geometry);
  const auto check = [&body](const char* option) {
    std::string error;
    if (!is_well_formed(body, &error)) {
      throw OptionError("`" + std::string(option) + "`: " + error, Code::OptionValue, option);
    }
  };
  if (change.mass) {
    body.mass = *change.mass;
    check("payload_mass");
  }
  if (!change.center_of_mass.empty()) {
    count("payload_com", change.center_of_mass.size(), {3}, "3 comma-separated numbers x,y,z");
    body.center_of_mass = Eigen::Vector3d(change.center_of_mass[0], change.center_of_mass[1], change.center_of_mass[2]);
    check("payload_com");
  }
  if (!change.inertia.empty()) {
    count("payload_inertia", change.inertia.size(), {3, 6, 9},
          "3 (the diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz) or 9 numbers");
    body.inertia = inertia_of(change.inertia);
    check("payload_inertia");
  }
  return body;
}

std::string payload_json(const RigidBodyInertia& body) {
  nlohmann::json inertia = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) inertia.push_back({body.inertia(i, 0), body.inertia(i, 1), body.inertia(i, 2)});
  const nlohmann::json out = {
      {"mass", body.mass},
      {"center_of_mass", {body.center_of_mass(0), body.center_of_mass(1), body.center_of_mass(2)}},
      {"inertia", inertia}};
  return out.dump();
}

void check_simulate_request(const SimulateRequest& request, const std::vector<std::string_view>& given) {
  check_option_combination(simulate_option_table(), given);
  if (!request.noise_given) {
    throw OptionError("give the noise: `noise_var` V, or `noise_std_a` S and `noise_std_b` S", Code::OptionConflict,
                      "noise_var");
  }
}

SimulateResult run_simulate(const SimulateRequest& request, const io::ReadOptions& read) {
  SimulateResult result;
  result.seed = request.seed;
  std::optional<Geometry> geometry;
  if (request.geometry.given()) {
    geometry = request.geometry.value ? *request.geometry.value : read_geometry(request.geometry.path);
    const std::string name = request.geometry.path.empty() ? std::string("given") : request.geometry.path;
    if (request.payload.given()) {
      result.payload = payload_with(*geometry, request.payload);
      result.truth = joint_space_mass_matrix(*geometry, *result.payload);
      result.truth_source = "geometry " + name + " with the payload of --payload-*";
    } else {
      result.truth = joint_space_mass_matrix(*geometry);
      result.truth_source = "geometry " + name;
    }
  } else if (!request.truth.given() || request.truth.path == "thesis") {
    result.truth = thesis_mass_matrix();
    result.truth_source = "thesis eq. 6.1";
  } else {
    const std::string name = request.truth.from_file() ? request.truth.path : std::string("the truth given");
    if (request.truth.from_file()) {
      io::Table table = io::read_table(request.truth.path, read);
      result.warnings = std::move(table.warnings);
      result.truth = std::move(table.values);
    } else {
      result.truth = request.truth.values;
    }
    if (result.truth.rows() != result.truth.cols()) {
      const std::string message = "the true M_p must be square, not " + std::to_string(result.truth.rows()) + "x" +
                                  std::to_string(result.truth.cols());
      if (request.truth.from_file()) throw io::DataError(name, 0, 0, message, Code::DataShape);
      throw InputError("`truth`: " + message, Code::DataShape, "truth");
    }
    if (!result.truth.isApprox(result.truth.transpose())) {
      result.warnings.emplace_back(Code::NotSymmetric, name + ": the true M_p is not symmetric", "truth");
    }
    result.truth_source = name;
  }
  SimulationOptions options = request.options;
  if (!request.preload.empty()) {
    const Eigen::Index n = result.truth.rows();
    if (request.preload.size() != 1 && Eigen::Index(request.preload.size()) != n) {
      throw OptionError("`preload` has " + std::to_string(request.preload.size()) + " values for " + std::to_string(n) +
                            " struts: give one for every strut, or one per strut",
                        Code::OptionValue, "preload");
    }
    options.rest_force = request.preload.size() == 1
                             ? Eigen::VectorXd::Constant(n, request.preload.front())
                             : Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(request.preload.data(), n));
  }
  std::string error;
  if (!options.is_valid(&error)) throw OptionError(error, Code::OptionValue);
  for (Warning& w : simulation_warnings(result.truth, options)) result.warnings.push_back(std::move(w));
  // The payload's simulate draws what simulate(M, options, seed) draws for its M.
  result.data = result.payload ? simulate(*geometry, *result.payload, options, request.seed)
                               : simulate(result.truth, options, request.seed);
  result.options = std::move(options);
  return result;
}

std::string simulation_json(const SimulateResult& result) {
  const SimulationOptions& options = result.options;
  nlohmann::json settings;
  settings["samples"] = options.samples;
  settings["noise_var"] = options.noise_var;
  settings["force_noise_var"] = options.force_noise_var.value_or(options.noise_var);
  settings["signal_var"] = options.signal_var;
  settings["distribution"] = std::string(to_string(options.distribution));
  settings["truth"] = result.truth_source;
  if (result.payload) settings["payload"] = nlohmann::json::parse(payload_json(*result.payload));
  settings["seed"] = result.seed;
  if (options.noise_std_a) settings["noise_std_a"] = std::vector<double>(options.noise_std_a->begin(), options.noise_std_a->end());
  if (options.noise_std_b) settings["noise_std_b"] = std::vector<double>(options.noise_std_b->begin(), options.noise_std_b->end());
  settings["scale_b"] = options.scale_b;
  settings["rest_samples"] = options.rest_samples;
  if (options.rest_force.size() > 0) {
    settings["preload"] = std::vector<double>(options.rest_force.begin(), options.rest_force.end());
  }
  settings["files"] = {{"A", "A.csv"}, {"B", "B.csv"}, {"truth", "truth.csv"}};
  if (options.rest_samples > 0) {
    settings["files"]["rest_A"] = "rest_A.csv";
    settings["files"]["rest_B"] = "rest_B.csv";
  }
  return settings.dump(2) + "\n";
}

std::string write_simulation(const SimulateResult& result, const std::string& directory,
                             const std::string& geometry_path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw io::DataError(directory, 0, 0, "cannot create the output directory: " + error.message());
  const fs::path dir(directory);
  const SimulationOptions& options = result.options;
  const Measurements& data = result.data;
  io::write_csv((dir / "A.csv").string(), data.A);
  io::write_csv((dir / "B.csv").string(), data.B);
  // The true X of the data written: M_p in B's units over A's.
  io::write_csv((dir / "truth.csv").string(), result.truth * options.scale_b);
  if (options.rest_samples > 0) {
    io::write_csv((dir / "rest_A.csv").string(), data.rest_A);
    io::write_csv((dir / "rest_B.csv").string(), data.rest_B);
  }
  io::write_text((dir / "simulation.json").string(), simulation_json(result));

  std::ostringstream out;
  out << "wrote " << (dir / "A.csv").string() << " (" << data.A.rows() << "x" << data.A.cols()
      << " accelerations), " << (dir / "B.csv").string() << " (forces), " << (dir / "truth.csv").string()
      << " (M_p: " << result.truth_source << "), " << (dir / "simulation.json").string();
  if (options.rest_samples > 0) {
    out << ", " << (dir / "rest_A.csv").string() << " and " << (dir / "rest_B.csv").string() << " ("
        << options.rest_samples << " rows at rest)";
  }
  out << "\n";
  // The next step only when it can succeed: identify needs at least as many samples as columns.
  if (options.samples >= result.truth.rows()) {
    out << "identify M_p from them with:\n  spdfit hexapod identify " << (dir / "A.csv").string() << ' '
        << (dir / "B.csv").string() << " --truth " << (dir / "truth.csv").string()
        << (result.payload ? " --physical --geometry " + geometry_path : std::string());
    if (options.rest_samples > 0) {
      out << " --rest-a " << (dir / "rest_A.csv").string() << " --rest-b " << (dir / "rest_B.csv").string();
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace spdfit::hexapod
