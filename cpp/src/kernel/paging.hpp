// How a large batch output's pages are faulted in ahead of its stores (fk_batch.cpp's blocks). A
// new output (numpy's np.empty of 128 MB) arrives as pages the kernel has not mapped yet: each is
// faulted in and zeroed on first write, on the calling thread. Faulting them in ahead, one 2 MB
// page at a time with one system call, lets the stores find lines zeroed shortly before.
#pragma once

#include <algorithm>
#include <cstdint>

namespace robokin {

namespace kernel {

// Faults in every page that [begin, end) touches with one system call (Linux >= 5.14), instead of
// one trap per page on first write (4 KB pages), and zeroes them in the kernel; with numpy's huge
// pages (it asks for them on large arrays) one call may fault in 2 MB. Nothing is written: a page
// shared with a neighbouring range (another thread's) is left as it is. Without the call (older
// kernels, other systems) the pages fault in as they are written.
void populate_for_writing(double* begin, double* end);

// A large frame output is faulted in a 2 MB page at a time (numpy's huge pages, else 512 small
// ones with one call), one page ahead of the stores, so that they find lines the kernel zeroed
// shortly before. Faulting in the whole output first, then streaming the frames past the cache,
// writes it to memory twice. One page ahead measured faster than chunks, than just in time and
// than two pages ahead (benchmarks/README.md); why it beats just in time was not isolated.
constexpr std::uintptr_t kFaultAhead = std::uintptr_t{1} << 21;

// The first configuration after `upto` whose frame lies wholly beyond the next 2 MB boundary from
// the frame of `upto` on (at most `end`): faulting in [.., that) faults in the page after upto's.
inline long next_page_end(const double* out, long width, long upto, long end) {
  const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(out + width * upto);
  const std::uintptr_t edge = (at + kFaultAhead) & ~(kFaultAhead - 1);
  return std::min(end, upto + static_cast<long>((edge - at) / (sizeof(double) * width)) + 1);
}

}  // namespace kernel

}  // namespace robokin
