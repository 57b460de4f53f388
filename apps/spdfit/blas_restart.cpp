#include "blas_restart.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "spdfit/blas.hpp"

namespace spdfit::cli {

namespace {

// Set for the restarted process to "<reported core>:<chosen core>"; removed by it.
constexpr const char* kRestartMarker = "SPDFIT_BLAS_REEXEC";
constexpr const char* kTestExecutableVariable = "SPDFIT_TEST_BLAS_EXE";
constexpr const char* kSelf = "/proc/self/exe";

// What this run knows about the choice of kernels, for report_blas_core.
struct BlasCoreState {
  BlasCoreCheck check;
  bool restarted = false;      // this process is the restarted one
  std::string restarted_from;  // the core reported before the restart (empty: marker not ours)
  std::string restart_error;   // why the restart failed (empty: it did not fail)
};

BlasCoreState& state() {
  static BlasCoreState the_state;
  return the_state;
}

std::string verbose_line(const BlasCoreState& s) {
  const BlasCoreCheck& check = s.check;
  const std::string core = blas_core_name();
  if (core.empty()) return "the BLAS is not OpenBLAS: no choice of kernels to report";
  if (s.restarted && !s.restarted_from.empty() && !check.user_coretype.empty()) {
    return "OpenBLAS reported core '" + s.restarted_from + "'" +
           (check.cpu.empty() ? "" : " on a CPU with " + check.cpu) + ": restarted with " +
           kOpenBlasCoreVariable + "=" + check.user_coretype + " (OpenBLAS core now: " + core + ")";
  }
  if (!s.restart_error.empty()) {
    return "OpenBLAS core: " + core + " (it reported '" + check.reported + "' on a CPU with " + check.cpu +
           "; the restart with " + kOpenBlasCoreVariable + "=" + check.suggested +
           " failed: " + s.restart_error + ")";
  }
  std::string line = "OpenBLAS core: " + core;
  if (!check.user_coretype.empty()) {
    line += std::string(" (") + kOpenBlasCoreVariable + "=" + check.user_coretype +
            ", set before spdfit ran)";
  } else {
    line += " (chosen by OpenBLAS)";
  }
  if (check.from_test_switch) {
    line += std::string("; ") + kTestBlasCoreVariable + "=" + check.reported + " is set";
  }
  return line;
}

}  // namespace

void restart_for_blas_core(char** argv) {
  BlasCoreState& s = state();
  if (const char* marker = std::getenv(kRestartMarker)) {
    // The restarted process (or a marker someone else set: that, too, stops a restart, which
    // guards against a loop whatever the environment holds).
    const std::string value = marker;
    ::unsetenv(kRestartMarker);
    s.restarted = true;
    const std::size_t colon = value.find(':');
    if (colon != std::string::npos) s.restarted_from = value.substr(0, colon);
    s.check = check_blas_core();
    return;
  }
  s.check = check_blas_core();
  const std::string& core = s.check.suggested;
  if (core.empty() || argv == nullptr || argv[0] == nullptr) return;

  const char* const previous_coretype = std::getenv(kOpenBlasCoreVariable);  // unset or ""
  const bool had_coretype = previous_coretype != nullptr;
  const std::string marker = s.check.reported + ":" + core;
  ::setenv(kOpenBlasCoreVariable, core.c_str(), 1);
  ::setenv(kRestartMarker, marker.c_str(), 1);
  const char* test_executable = std::getenv(kTestExecutableVariable);
  const char* executable = test_executable && *test_executable ? test_executable : kSelf;
  ::execv(executable, argv);
  const int error = errno;

  // Still here: the restart failed (no /proc, the binary replaced on disk, ...). Run on with the
  // kernels OpenBLAS chose, in the environment as it was.
  s.restart_error = std::string(executable) + ": " + std::strerror(error);
  if (had_coretype) {
    ::setenv(kOpenBlasCoreVariable, "", 1);
  } else {
    ::unsetenv(kOpenBlasCoreVariable);
  }
  ::unsetenv(kRestartMarker);
}

void report_blas_core(const GlobalOptions& global) {
  const BlasCoreState& s = state();
  if (!s.restart_error.empty()) {
    warn(global, "OpenBLAS runs its generic '" + s.check.reported + "' kernels on this CPU, which has " +
                     s.check.cpu + "; restarting with " + kOpenBlasCoreVariable + "=" +
                     s.check.suggested + " failed (" + s.restart_error + "). Set " +
                     kOpenBlasCoreVariable + "=" + s.check.suggested +
                     " before running spdfit for the faster kernels");
  }
  const std::string kernels = kernel_isa_warning();
  if (!kernels.empty()) warn(global, kernels);
  if (global.verbose) {
    std::cerr << "spdfit: " << verbose_line(s) << '\n';
    std::cerr << "spdfit: own kernels (the block QR): " << kernel_isa_report() << '\n';
  }
}

}  // namespace spdfit::cli
