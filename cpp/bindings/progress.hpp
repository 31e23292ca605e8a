// robokin::Progress for the long calls made from Python. Ctrl-C stops them: every kPoll the
// GIL is taken for a moment to run Python's signal handlers (an exception they raise, such as
// KeyboardInterrupt, ends the computation through robokin::Interrupted and is what Python sees).
// When stderr is a terminal and a call has run for more than two seconds, a bar is drawn there.
// Nothing else of Python runs on the way, so no signal can be swallowed by a drawing error; and
// nothing touches Python at all in a call shorter than kPoll.
#pragma once

#include <pybind11/pybind11.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "robokin/progress.hpp"

namespace robokin::bind {

class PythonProgress final : public Progress {
 public:
  // Made with the GIL held, before the computation releases it; `what` names the call on the bar.
  explicit PythonProgress(const char* what)
      : what_(what), start_(Clock::now()), next_(start_ + kPoll), uncaught_(std::uncaught_exceptions()) {}
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;

  // Ends the bar's line: at 100 % when the call completed, where it stood when it was stopped.
  ~PythonProgress() override {
    if (!shown_) return;
    if (std::uncaught_exceptions() == uncaught_) done_ = total_;
    draw("\n");
  }

  // Called without the GIL, on the thread that started the call.
  bool update(long done, long total) override {
    const Clock::time_point now = Clock::now();
    if (now < next_) return true;
    next_ = now + kPoll;
    {
      pybind11::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) return false;
    }
    done_ = done, total_ = total;
    elapsed_ = std::chrono::duration<double>(now - start_).count();
    if (elapsed_ >= kDelay && now >= next_draw_ && (shown_ || isatty(STDERR_FILENO))) {
      next_draw_ = now + kRedraw;
      draw("");
    }
    return true;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kPoll{50}, kRedraw{200};
  static constexpr double kDelay = 2.0;  // seconds before a bar appears
  static constexpr int kWidth = 30;

  void draw(const char* end) {
    const double share = total_ > 0 ? std::min(1.0, static_cast<double>(done_) / total_) : 1.0;
    const int filled = static_cast<int>(share * kWidth + 0.5);
    char left[48] = "";
    if (share > 0 && share < 1) std::snprintf(left, sizeof left, ", %.0f s left", elapsed_ * (1 - share) / share);
    const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
    char line[256];
    const int n = std::snprintf(line, sizeof line, "\r%s: [%s] %3.0f%% (%.0f s%s)%s", what_, bar.c_str(), 100 * share,
                                elapsed_, left, end);
    if (n > 0 && ::write(STDERR_FILENO, line, static_cast<size_t>(std::min<int>(n, sizeof line - 1))) > 0) shown_ = true;
  }

  const char* what_;
  Clock::time_point start_, next_, next_draw_{};
  int uncaught_;
  bool shown_ = false;
  long done_ = 0, total_ = 1;
  double elapsed_ = 0;
};

// The shape of every long core call made from Python: fn(&progress) run with the GIL released and
// a PythonProgress named `what` polling for Ctrl-C (and drawing the bar). What fn reads from Python
// is converted before, with the GIL; fn returns a C++ value, which the caller checks after.
template <class Fn>
auto released(const char* what, Fn&& fn) {
  PythonProgress progress(what);
  pybind11::gil_scoped_release release;
  return fn(&progress);
}

// fn() with the GIL released, for a core call that takes no Progress.
template <class Fn>
auto released(Fn&& fn) {
  pybind11::gil_scoped_release release;
  return fn();
}

}  // namespace robokin::bind
