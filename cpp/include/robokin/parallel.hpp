// Splits a batch over the machine's cores. Callers release the GIL before.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "robokin/progress.hpp"

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

// Calls body(begin, end) on contiguous blocks of [0, count), on one thread when the batch is
// small (min_per_thread items is the least work worth a thread). Blocks are handed out from a
// shared counter, so the calling thread reports to `progress` between its blocks, and every thread
// stops taking blocks once the caller asks to stop or a body throws. The exception (Interrupted,
// or the body's own) is rethrown here after all threads have joined: it never escapes a thread.
template <class Body>
void parallel_for(long count, long min_per_thread, Body body, Progress* progress = nullptr) {
  if (count <= 0) return;
  const long least = std::max(1L, min_per_thread);
  const long threads = std::min(max_threads(), count / least);
  // A few blocks per thread (balance), none above 16 x min_per_thread (progress is heard often);
  // fewer, larger blocks are faster for the streaming batch FK.
  const long block = std::clamp(count / (std::max(1L, threads) * 8), least, 16 * least);
  const long blocks = (count + block - 1) / block;
  std::atomic<long> next{0}, finished{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&](bool caller) {
    try {
      for (long b; !stop.load(std::memory_order_relaxed) && (b = next.fetch_add(1)) < blocks;) {
        body(b * block, std::min(count, (b + 1) * block));
        const long done = finished.fetch_add(1) + 1;
        if (caller) report(progress, std::min(count, done * block), count);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (long t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work, false);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones running (and this one) do the rest
    }
  }
  work(true);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace robokin
