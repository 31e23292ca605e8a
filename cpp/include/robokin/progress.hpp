// How a long computation reports how far it has got and learns that its caller wants it stopped
// (Ctrl-C in Python), without the core knowing about Python.
#pragma once

#include <stdexcept>

namespace robokin {

class Progress {
 public:
  virtual ~Progress() = default;
  // Called on the thread that started the computation, often (every block of a batch); cheap
  // implementations check a clock first. Returns false when the computation should stop.
  virtual bool update(long done, long total) = 0;
};

// Thrown out of a computation whose Progress asked it to stop.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

// Reports to progress (when there is one) and throws Interrupted when it asks to stop.
inline void report(Progress* progress, long done, long total) {
  if (progress && !progress->update(done, total)) throw Interrupted();
}

// Part k of a computation made of `parts` equal parts, reported as a share of the whole.
class PartProgress final : public Progress {
 public:
  PartProgress(Progress* whole, long k, long parts) : whole_(whole), k_(k), parts_(parts) {}
  bool update(long done, long total) override {
    return !whole_ || whole_->update(k_ * total + done, parts_ * total);
  }

 private:
  Progress* whole_;
  long k_, parts_;
};

}  // namespace robokin
