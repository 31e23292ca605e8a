// Splits a batch over the machine's cores. Callers release the GIL before; the body must not throw.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace robokin {

// Calls body(begin, end) on contiguous slices of [0, count); one slice when the batch is small.
template <class Body>
void parallel_for(long count, long min_per_thread, Body body) {
  const long cores = std::max(1u, std::thread::hardware_concurrency());
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
