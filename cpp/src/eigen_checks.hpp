// Included first in every file of the sanitizer build (ROBOKIN_SANITIZE): Eigen's own checks of
// sizes and indices are on there (the release build compiles them out) and throw instead of
// aborting, so a misuse surfaces in the test suite as an exception at its source.
#pragma once

#include <stdexcept>

#define eigen_assert(x) \
  do {                  \
    if (!(x)) throw std::logic_error("Eigen check failed: " #x); \
  } while (0)
