#include "progress_line.hpp"

#include <memory>
#include <optional>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace spdfit::cli {

namespace {
// Nothing for work that ends within this; then at most one update per kInterval. The tests set
// SPDFIT_TEST_PROGRESS_NOW=1 to see the line at once, without a run that lasts a second.
constexpr std::chrono::milliseconds kDelay{1000};
constexpr std::chrono::milliseconds kInterval{250};

std::chrono::milliseconds delay() {
  const char* now = std::getenv("SPDFIT_TEST_PROGRESS_NOW");
  return now != nullptr && std::string(now) == "1" ? std::chrono::milliseconds{0} : kDelay;
}

std::string duration_text(double seconds) {
  char buffer[32];
  const auto s = static_cast<long>(std::lround(seconds));
  if (s < 60) {
    std::snprintf(buffer, sizeof buffer, "%ld s", s);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  }
  return buffer;
}
}  // namespace

ProgressLine::ProgressLine(const GlobalOptions& global, std::string what, std::uint64_t bytes)
    : enabled_(!global.quiet && ::isatty(STDERR_FILENO) == 1),
      what_(std::move(what)),
      bytes_(bytes),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressLine::~ProgressLine() {
  if (shown_) std::fputs("\r\033[K", stderr);
}

ProgressCallback ProgressLine::callback() {
  if (!enabled_) return {};
  return [this](double fraction) { update(fraction); };
}

void ProgressLine::update(double fraction) {
  const auto now = std::chrono::steady_clock::now();
  static const std::chrono::milliseconds wait = delay();
  if (now - start_ < wait || (shown_ && now - last_ < kInterval && fraction < 1.0)) return;
  last_ = now;
  shown_ = true;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::string line = "spdfit: " + what_;
  char buffer[64];
  if (fraction > 0.0) {
    std::snprintf(buffer, sizeof buffer, " %3.0f%%", 100.0 * fraction);
    line += buffer;
  }
  if (bytes_ > 0 && elapsed > 0.0) {
    std::snprintf(buffer, sizeof buffer, ", %.0f MB/s", fraction * static_cast<double>(bytes_) / elapsed / 1e6);
    line += buffer;
  }
  if (fraction > 0.0 && fraction < 1.0) line += ", " + duration_text(elapsed * (1.0 - fraction) / fraction) + " left";
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
}

std::function<void(std::size_t, std::size_t)> trials_progress(const GlobalOptions& global, const std::string& label) {
  auto line = std::make_shared<std::optional<ProgressLine>>();
  line->emplace(global, label);
  ProgressCallback update = (*line)->callback();
  if (!update) return {};
  return [line, update](std::size_t done, std::size_t total) {
    if (!line->has_value()) return;
    if (done < total) {
      update(static_cast<double>(done) / static_cast<double>(total));
    } else {
      line->reset();  // cleared before the results are printed
    }
  };
}

}  // namespace spdfit::cli
