// Splits a batch over the machine's cores. Callers release the GIL before; the body must not throw.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <thread>
#include <vector>

namespace robokin {

// Threads a batch may use: the machine's cores, or ROBOKIN_NUM_THREADS when set to a positive
// integer (read at every batch call, so it can be changed at run time; benchmarks set it to 1).
inline long max_threads() {
  if (const char* env = std::getenv("ROBOKIN_NUM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && n >= 1) return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

// Calls body(begin, end) on contiguous slices of [0, count); one slice when the batch is small.
template <class Body>
void parallel_for(long count, long min_per_thread, Body body) {
  const long cores = max_threads();
  const long threads = std::min(cores, count / std::max(1L, min_per_thread));
  if (threads <= 1) {
    body(0L, count);
    return;
  }
  std::vector<std::thread> pool;
  const long chunk = (count + threads - 1) / threads;
  for (long t = 1; t < threads; ++t) {
    const long begin = t * chunk, end = std::min(count, begin + chunk);
    if (begin < end) pool.emplace_back([=] { body(begin, end); });
  }
  body(0L, std::min(count, chunk));
  for (auto& th : pool) th.join();
}

}  // namespace robokin
