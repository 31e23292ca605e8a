// robokin::Progress for the long calls made from Python. Ctrl-C stops them: about every 50 ms the
// GIL is taken for a moment to run Python's signal handlers (a KeyboardInterrupt then ends the
// computation through robokin::Interrupted). After a couple of seconds in an interactive terminal,
// robokin._progress draws a bar. Cheap when a call is short: nothing touches Python before 50 ms.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>

#include "robokin/progress.hpp"

namespace robokin::bind {

namespace py = pybind11;

class PythonProgress final : public Progress {
 public:
  // Made with the GIL held, before the computation releases it; `what` names the call on the bar.
  explicit PythonProgress(const char* what)
      : what_(what), start_(Clock::now()), next_(start_ + kEvery), uncaught_(std::uncaught_exceptions()) {}
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;

  // Destroyed with the GIL held (after the release scope), also while an exception unwinds.
  ~PythonProgress() override {
    if (!bar_) return;
    py::error_scope keep;  // a pending KeyboardInterrupt stays pending
    try {
      bar_.attr("close")(std::uncaught_exceptions() == uncaught_);
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("closing robokin's progress bar");
    }
  }

  // Called without the GIL, on the thread that started the call.
  bool update(long done, long total) override {
    const Clock::time_point now = Clock::now();
    if (now < next_) return true;
    next_ = now + kEvery;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) return false;
    try {
      if (!bar_) bar_ = py::module_::import("robokin._progress").attr("Bar")(what_);
      bar_.attr("update")(done, total, std::chrono::duration<double>(now - start_).count());
    } catch (py::error_already_set& e) {
      // Ctrl-C while the bar was drawn stops the call; a bar that cannot be drawn does not.
      if (e.matches(PyExc_KeyboardInterrupt)) {
        e.restore();
        return false;
      }
      e.discard_as_unraisable("drawing robokin's progress bar");
    }
    return true;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kEvery{50};
  const char* what_;
  Clock::time_point start_, next_;
  int uncaught_;
  py::object bar_;
};

}  // namespace robokin::bind
