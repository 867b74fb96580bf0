#pragma once
// A one-line progress report on stderr for long runs:
//   [flat_blade] 45.2% t=1.234/3.500 s step 12345 | 3.1e6 particle-steps/s | ETA 0:42
// On a terminal the line is redrawn in place (at most twice a second); otherwise (a log file,
// a batch job) a plain line is printed at every further 10 % so logs stay short, and the final
// report is not printed again when the last plain line already showed that step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

#include "cosmpm/core/types.hpp"

#if __has_include(<unistd.h>)
#include <unistd.h>
#endif

namespace cosmpm::io {

class ProgressReporter {
 public:
  enum class Style { automatic, terminal, plain };
  using Clock = std::chrono::steady_clock;

  // `end_time`: simulated time at which the run ends; `particles`: for the throughput.
  ProgressReporter(std::string name, double end_time, Index particles, std::FILE* out = stderr,
                   Style style = Style::automatic)
      : name_(std::move(name)), end_time_(end_time), particles_(particles), out_(out) {
    terminal_ = style == Style::terminal || (style == Style::automatic && is_terminal(out_));
  }

  // Reports the state after a step; cheap when nothing is printed.
  void update(double time, std::int64_t step) { report(time, step, Clock::now(), false); }

  // The final report, ending the line.
  void finish(double time, std::int64_t step) { report(time, step, Clock::now(), true); }

  // As update/finish, at a given wall-clock instant (tests).
  void report(double time, std::int64_t step, Clock::time_point now, bool final) {
    if (!started_) {
      started_ = true;
      first_time_ = time;
      first_step_ = step;
      first_wall_ = now;
      last_print_ = now - std::chrono::seconds(1);
    }
    const double fraction = end_time_ > 0.0 ? std::clamp(time / end_time_, 0.0, 1.0) : 1.0;
    if (final && !terminal_ && printed_ && step == last_step_printed_) return;
    if (!final) {
      if (terminal_) {
        if (now - last_print_ < std::chrono::milliseconds(500)) return;
      } else {
        const int decile = static_cast<int>(std::floor(fraction * 10.0));
        if (decile <= last_decile_) return;
        last_decile_ = decile;
      }
    }
    last_print_ = now;
    printed_ = true;
    last_step_printed_ = step;
    const double elapsed = std::chrono::duration<double>(now - first_wall_).count();
    const double rate = elapsed > 0.0 ? static_cast<double>(particles_) *
                                            static_cast<double>(step - first_step_) / elapsed
                                      : 0.0;
    const double done = time - first_time_;
    const double eta = done > 0.0 && elapsed > 0.0 ? elapsed * (end_time_ - time) / done : -1.0;
    const std::string line = format_line(name_, fraction, time, end_time_, step, rate, eta);
    if (terminal_) {
      std::fprintf(out_, "\r%s%s", line.c_str(), final ? "\n" : "");
    } else {
      std::fprintf(out_, "%s\n", line.c_str());
    }
    std::fflush(out_);
  }

  // The report line; eta_seconds < 0 means unknown.
  static std::string format_line(const std::string& name, double fraction, double time,
                                 double end_time, std::int64_t step, double rate,
                                 double eta_seconds) {
    char head[256];
    std::snprintf(head, sizeof(head), "[%s] %.1f%% t=%.3f/%.3f s step %lld | ", name.c_str(),
                  100.0 * fraction, time, end_time, static_cast<long long>(step));
    return std::string(head) + format_rate(rate) + " particle-steps/s | ETA " +
           format_duration(eta_seconds);
  }

  // 3.1e6 style: two significant digits, short exponent.
  static std::string format_rate(double rate) {
    if (!(rate > 0.0) || !std::isfinite(rate)) return "0";
    int exponent = static_cast<int>(std::floor(std::log10(rate)));
    double mantissa = std::round(rate / std::pow(10.0, exponent) * 10.0) / 10.0;
    if (mantissa >= 10.0) {
      mantissa /= 10.0;
      ++exponent;
    }
    char text[32];
    std::snprintf(text, sizeof(text), "%.1fe%d", mantissa, exponent);
    return text;
  }

  // m:ss below an hour, h:mm:ss above; "--" when unknown.
  static std::string format_duration(double seconds) {
    if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "--";
    const auto total = static_cast<long long>(std::llround(seconds));
    char text[48];
    if (total >= 3600) {
      std::snprintf(text, sizeof(text), "%lld:%02lld:%02lld", total / 3600, (total / 60) % 60,
                    total % 60);
    } else {
      std::snprintf(text, sizeof(text), "%lld:%02lld", total / 60, total % 60);
    }
    return text;
  }

 private:
  static bool is_terminal(std::FILE* out) {
#if __has_include(<unistd.h>)
    return ::isatty(::fileno(out)) != 0;
#else
    (void)out;
    return false;
#endif
  }

  std::string name_;
  double end_time_;
  Index particles_;
  std::FILE* out_;
  bool terminal_ = false;
  bool started_ = false;
  double first_time_ = 0.0;
  std::int64_t first_step_ = 0;
  Clock::time_point first_wall_{};
  Clock::time_point last_print_{};
  int last_decile_ = 0;
  bool printed_ = false;
  std::int64_t last_step_printed_ = 0;
};

}  // namespace cosmpm::io
