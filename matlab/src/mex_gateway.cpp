// spdfit_mex: the one MEX function behind the spdfit package's M-files (+spdfit/*.m), which call
// it as spdfit_mex('fit', A, B, method, name, value, ...), spdfit_mex('nearest', C, ...) and
// spdfit_mex('solve', A, b, ...). It converts MATLAB's arrays, runs the library, and returns the
// estimate and the library's JSON rendering of the result as a struct.
//
// No C++ exception crosses into MATLAB: everything that can throw runs inside `run`, whose
// objects are destroyed before mexErrMsgIdAndTxt (which does not return) raises the error with
// an identifier: 'spdfit:UsageError' (an option or argument misused), 'spdfit:DataError' (data
// the library cannot fit) or 'spdfit:NumericalError' (valid data without an answer).
#include <algorithm>
#include <cctype>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mex.h"
#include "mex_arrays.hpp"
#include "mex_pairs.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/solve_request.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "spdfit/option_spelling.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"
#include "spdfit/render.hpp"

namespace spdfit::matlab {

namespace {

// A method named in any case, as option names are matched ('SPD-TLS', 'Auto'): MATLAB users
// expect names to be case-insensitive.
std::optional<Method> method_named(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return parse_method(text);
}

// A result's numerical failure (Code::NumericalFailure): 'spdfit:NumericalError'.
struct NumericalError : std::runtime_error, Coded {
  explicit NumericalError(const std::string& message) : std::runtime_error(message), Coded(Code::NumericalFailure, {}) {}
};

// The warnings as an n x 2 cell {identifier, text}, which spdfit_call.m raises with `warning`
// (MATLAB and Octave would prefix the MEX function's name to a warning raised here). The
// identifier comes from the warning's code (spdfit/outcome.hpp), so that users can silence one kind.
mxArray* warnings_cell(const std::vector<Warning>& warnings) {
  mxArray* out = mxCreateCellMatrix(warnings.size(), 2);
  for (std::size_t k = 0; k < warnings.size(); ++k) {
    const std::string text = spell_options(warnings[k].text, Frontend::Matlab);
    mxSetCell(out, static_cast<mwIndex>(k), mxCreateString(matlab_identifier(warnings[k].code).c_str()));
    mxSetCell(out, static_cast<mwIndex>(k + warnings.size()), mxCreateString(text.c_str()));
  }
  return out;
}

// The name-value pairs from argument `first` on.
std::vector<NameValue> pairs_from(std::string_view function, int nrhs, const mxArray* prhs[], int first) {
  if ((nrhs - first) % 2 != 0) {
    throw UsageError("spdfit." + std::string(function) + ": options come in name-value pairs ('" +
                     std::string(function == "fit" ? "Bootstrap', 1000" : "MaxIterations', 500") + ")");
  }
  std::vector<NameValue> out;
  for (int k = first; k < nrhs; k += 2) {
    out.push_back({read_text(prhs[k], "an option's name (argument " + std::to_string(k) + ")"), prhs[k + 1]});
  }
  return out;
}

void need_arguments(std::string_view function, int nrhs, int at_least, const char* usage) {
  if (nrhs < at_least) throw UsageError("spdfit." + std::string(function) + " needs " + usage);
}

void fit_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("fit", nrhs, 3, "A and B: [X, info] = spdfit.fit(A, B, method, name, value, ...)");
  Eigen::MatrixXd A = read_matrix(prhs[1], "A");
  Eigen::MatrixXd B = read_matrix(prhs[2], "B");
  // Row vectors where columns are meant (one unknown): m samples of a scalar X, as the CLI's
  // reader takes a file of one row.
  if (A.rows() == 1 && B.rows() == 1 && A.cols() > 1 && A.cols() == B.cols()) {
    A.transposeInPlace();
    B.transposeInPlace();
  }
  // The fourth argument is the method when it names one, or when the arguments after it pair up;
  // otherwise it is an option's name ('Bootstrap', 1000 without a method).
  bool has_method = false;
  if (nrhs >= 4 && mxIsChar(prhs[3])) {
    has_method = method_named(read_text(prhs[3], "the method")).has_value() || (nrhs - 4) % 2 == 0;
  }
  FitRequest request;
  if (has_method) {
    const std::string method = read_text(prhs[3], "the method");
    const std::optional<Method> parsed = method_named(method);
    if (!parsed) {
      std::string names;
      for (Method m : kSelectableMethods) names += (names.empty() ? "" : ", ") + std::string(to_string(m));
      throw OptionError("unknown method '" + method + "' (methods: " + names + ")", Code::OptionValue, "method");
    }
    request.method = *parsed;
  }
  const std::vector<std::string_view> given =
      set_pairs(request, fit_option_table(), pairs_from("fit", nrhs, prhs, has_method ? 4 : 3), matlab_function("fit"));
  check_fit_request(request, given);
  const FitResult result = fit(A, B, request.method, request.resolved_options(A.cols(), B.cols()));
  if (!result.ok()) throw NumericalError(result.message);
  plhs[0] = write_matrix(result.X);
  plhs[1] = want_info ? write_json(to_json(result)) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(result.warnings);
}

void nearest_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("nearest", nrhs, 2, "C: [X, info] = spdfit.nearest(C, name, value, ...)");
  // The command's workflow: it reads the matrix options given as files ('Fixed', 'mask.csv'). C is
  // moved into it, not copied.
  NearestCommand command;
  command.matrix.values = read_matrix(prhs[1], "C");
  const std::vector<std::string_view> given = set_pairs(command.repair, nearest_option_table(),
                                                        pairs_from("nearest", nrhs, prhs, 2), matlab_function("nearest"));
  check_nearest_request(given);
  const NearestRun run = run_nearest(std::move(command));
  const NearestResult& result = run.result;
  plhs[0] = write_matrix(run.repair.factors_only ? result.F : result.X);
  plhs[1] = want_info ? write_json(to_json(result)) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(run.warnings);
}

void solve_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("solve", nrhs, 3, "A and b: [x, info] = spdfit.solve(A, b, name, value, ...)");
  SolveRequest request;
  request.a.values = read_matrix(prhs[1], "A");
  request.b.values = read_matrix(prhs[2], "b");
  set_pairs(request, solve_option_table(), pairs_from("solve", nrhs, prhs, 3), matlab_function("solve"));
  const SolveRun run = run_solve(request);
  if (const auto failure = run.failure()) throw NumericalError(failure->message);
  plhs[0] = write_matrix(run.result.solution);
  plhs[1] = want_info ? write_json(to_json(run.result)) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(run.warnings);
}

void identify_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("hexapod.identify", nrhs, 3,
                 "A and B: [result, text] = spdfit.hexapod.identify(A, B, name, value, ...)");
  hexapod::IdentifyRequest request;
  request.a.values = read_matrix(prhs[1], "A");
  request.b.values = read_matrix(prhs[2], "B");
  const std::vector<std::string_view> given = set_pairs(request, hexapod::identify_option_table(),
                                                        pairs_from("identify", nrhs, prhs, 3),
                                                        matlab_function("identify"));
  hexapod::check_identify_request(request, given);
  const hexapod::Identification result = hexapod::run_identify(request);
  if (const auto failure = result.failure()) throw NumericalError(failure->message);
  plhs[0] = write_json(hexapod::to_json(result));
  plhs[1] = want_info ? mxCreateString(hexapod::report(result).c_str()) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(result.warnings);
}

void payload_identify_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("payload.identify", nrhs, 2,
                 "the wrench: [result, text] = spdfit.payload.identify(W, 'Quaternion', Q, name, value, ...)");
  payload::PayloadSignals signals;
  signals.wrench = read_matrix(prhs[1], "W");
  // The signals' pairs are matrices; the others are the table's options.
  std::vector<NameValue> options;
  for (const NameValue& pair : pairs_from("payload.identify", nrhs, prhs, 2)) {
    const PayloadSignal* signal = nullptr;
    for (const PayloadSignal& s : payload_signals()) {
      if (same_name(camel_case(s.name), pair.name)) signal = &s;
    }
    if (signal == nullptr) {
      options.push_back(pair);
      continue;
    }
    if (mxIsEmpty(pair.value)) continue;
    const Eigen::MatrixXd value = read_matrix(pair.value, camel_case(signal->name));
    if (signal->matrix != nullptr) {
      signals.*(signal->matrix) = value;
    } else {
      signals.time = Eigen::Map<const Eigen::VectorXd>(value.data(), value.size());
    }
  }
  const auto& table = payload::identify_option_table();
  payload::IdentifyRequest request;
  const std::vector<std::string_view> given =
      set_pairs(request, table, options, matlab_function("payload.identify"));
  payload::check_identify_request(request, given);
  payload::PayloadEstimate estimate = payload::identify(signals, request);
  if (!estimate.ok()) throw NumericalError(estimate.message);
  plhs[0] = write_json(payload::to_json(estimate));
  plhs[1] = want_info ? mxCreateString(payload::report(estimate).c_str()) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(estimate.warnings);
}

void regress_command(bool want_info, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need_arguments("physical.regress", nrhs, 3, "Y and tau: [result, text] = spdfit.physical.regress(Y, tau, 'Bodies', K, ...)");
  const Eigen::MatrixXd Y = read_matrix(prhs[1], "Y");
  Eigen::MatrixXd tau = read_matrix(prhs[2], "tau");
  if (tau.rows() == 1 && tau.cols() == Y.rows()) tau.transposeInPlace();
  physical::RegressRequest request;
  std::vector<NameValue> options;
  for (const NameValue& pair : pairs_from("physical.regress", nrhs, prhs, 3)) {
    if (!same_name(pair.name, "NoiseCov")) {
      options.push_back(pair);
    } else if (!mxIsEmpty(pair.value)) {
      request.noise_cov = read_matrix(pair.value, "NoiseCov");
    }
  }
  const std::vector<std::string_view> given =
      set_pairs(request, physical::regress_option_table(), options, matlab_function("physical.regress"));
  physical::check_regress_request(request, given);
  if (!request.prior_path.empty()) request.prior = read_rigid_bodies(request.prior_path);
  const physical::RegressResult result = physical::regress(Y, tau, request);
  if (!result.ok()) throw NumericalError(result.message);
  plhs[0] = write_json(physical::to_json(result));
  plhs[1] = want_info ? mxCreateString(physical::report(result).c_str()) : mxCreateDoubleMatrix(0, 0, mxREAL);
  plhs[2] = warnings_cell(result.warnings);
}

// spdfit_mex(COMMAND, WANT_INFO, arguments...) -> [estimate, info, warnings]: the arguments after
// the first two are the package function's, which the commands index from 1 (prhs + 1).
void run(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  if (nrhs < 2 || nlhs != 3) {
    throw UsageError("spdfit_mex is called by the spdfit package's functions (spdfit.fit, ...), not directly");
  }
  const std::string command = read_text(prhs[0], "the command");
  const bool want_info = mxIsLogicalScalarTrue(prhs[1]);
  if (command == "fit") return fit_command(want_info, plhs, nrhs - 1, prhs + 1);
  if (command == "nearest") return nearest_command(want_info, plhs, nrhs - 1, prhs + 1);
  if (command == "solve") return solve_command(want_info, plhs, nrhs - 1, prhs + 1);
  if (command == "identify") return identify_command(want_info, plhs, nrhs - 1, prhs + 1);
  if (command == "payload.identify") return payload_identify_command(want_info, plhs, nrhs - 1, prhs + 1);
  if (command == "physical.regress") return regress_command(want_info, plhs, nrhs - 1, prhs + 1);
  throw UsageError("spdfit_mex has no command '" + command + "'");
}

}  // namespace

}  // namespace spdfit::matlab

extern "C" __attribute__((visibility("default"))) void mexFunction(int nlhs, mxArray* plhs[], int nrhs,
                                                                   const mxArray* prhs[]) {
  // Outside every scope that owns memory: mexErrMsgIdAndTxt does not return. The identifier comes
  // from the error's code (spdfit/outcome.hpp), never from its text.
  static std::string message, id;
  bool failed = false;
  try {
    spdfit::matlab::run(nlhs, plhs, nrhs, prhs);
  } catch (const std::exception& e) {
    failed = true;
    id = spdfit::matlab_identifier(spdfit::code_of(e));
    message = spdfit::spell_options(e.what(), spdfit::Frontend::Matlab);
  } catch (...) {
    failed = true;
    id = "spdfit:Error";
    message = "an unknown error";
  }
  if (failed) mexErrMsgIdAndTxt(id.c_str(), "%s", message.c_str());
}
