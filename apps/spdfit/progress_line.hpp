// The progress line of long runs (fit --stream, --bootstrap) on standard error: shown only when
// standard error is a terminal, warnings are not silenced (-q), and the work has run for a second.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "cli.hpp"
#include "spdfit/progress.hpp"

namespace spdfit::cli {

class ProgressLine {
 public:
  /// `what` names the work ("reading A and B"); `bytes` is its size when it is reading files,
  /// for a rate in MB/s (0: no rate).
  ProgressLine(const GlobalOptions& global, std::string what, std::uint64_t bytes = 0);
  ~ProgressLine();  ///< clears the line if it was shown
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// The callback for the library (StreamOptions::progress, FitOptions::progress); empty when the
  /// line is off, so the library does not even call it.
  ProgressCallback callback();

 private:
  void update(double fraction);

  bool enabled_;
  std::string what_;
  std::uint64_t bytes_;
  std::chrono::steady_clock::time_point start_, last_;
  bool shown_ = false;
};

/// A progress callback for Monte Carlo trials (MonteCarloOptions::progress) that shows `label`
/// on the progress line and clears it when the trials end; empty when the line is off.
std::function<void(std::size_t, std::size_t)> trials_progress(const GlobalOptions& global, const std::string& label);

}  // namespace spdfit::cli
