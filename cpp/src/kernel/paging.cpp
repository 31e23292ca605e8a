// paging.hpp's system call.
#include "paging.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace robokin {

namespace kernel {

void populate_for_writing(double* begin, double* end) {
#if defined(__linux__)
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23
#endif
  const std::uintptr_t page = 4096;
  const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(begin) & ~(page - 1);
  const std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(end) + page - 1) & ~(page - 1);
  if (b > a) madvise(reinterpret_cast<void*>(a), b - a, MADV_POPULATE_WRITE);
#else
  (void)begin, (void)end;
#endif
}

}  // namespace kernel

}  // namespace robokin
