// A chain's derived data, each part built at its first use (thread-safe) from the kinematics alone:
// one per chain, shared by its copies (which have the same kinematics), never changed afterwards.
#pragma once

#include "ik_starts.hpp"
#include "robokin/chain.hpp"
#include "robokin/ik_closed.hpp"

#include <memory>
#include <mutex>

namespace robokin {

struct Chain::Lazy {
  std::once_flag starts_once, layout_once;
  std::unique_ptr<const IkStarts> starts;      // Chain::ik_starts
  std::unique_ptr<const ClosedLayout> layout;  // Chain::closed_layout
};

}  // namespace robokin
