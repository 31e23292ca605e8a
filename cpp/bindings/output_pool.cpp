// Large outputs (new_float64 of kPooledBytes or more) in memory robokin maps itself; freed ones are
// kept, up to kKeptBytes, for the next outputs of their size.
//
// numpy takes an array's memory from malloc, and glibc gives a large block back to the kernel when
// it is freed (always above 32 MB, its largest mmap threshold). The next such output then comes
// back as fresh pages, which the kernel faults in and zeroes on the calling thread: more than half
// of a large batch FK's time. With the freed block kept, a loop of
// calls of one size (the previous result freed when the next is assigned) writes into pages it
// already has.
//
// A kept block is given to the kernel with MADV_FREE: under memory pressure it may take the pages
// back (they then fault in again, zeroed) instead of swapping them out. release_output_memory()
// unmaps them all. Elsewhere than Linux, numpy allocates as usual.
#include "arrays.hpp"
#include "bindings.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <mutex>
#include <new>
#endif

namespace robokin::bind {

#if defined(__linux__)
namespace {
constexpr std::size_t kHugePage = std::size_t{1} << 21;
// Blocks are whole pages: a block rounded up to huge pages would hold up to 2 MB more of memory
// (its last huge page faulted in whole) for every live output of that size.
const std::size_t kPage = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
// The freed outputs kept, newest first, while they add up to no more than this (the newest always).
constexpr std::size_t kKeptBytes = std::size_t{256} << 20;
constexpr std::size_t kMaxKept = kKeptBytes / kPooledBytes;

struct Block {
  void* data = nullptr;
  std::size_t bytes = 0;  // a multiple of kPage
};

struct Pool {
  std::mutex mutex;
  std::array<Block, kMaxKept> kept;  // [0, count), newest first
  std::size_t count = 0, bytes = 0;

  Block remove(std::size_t i) {
    const Block b = kept[i];
    for (std::size_t k = i + 1; k < count; ++k) kept[k - 1] = kept[k];
    --count, bytes -= b.bytes;
    return b;
  }
};

// Never destroyed: an array may be freed after static destructors have run.
Pool& pool() {
  static Pool* const p = new Pool;
  return *p;
}

void unmap(const Block& b) { munmap(b.data, b.bytes); }

// bytes (a multiple of kPage) of fresh memory starting on a 2 MB boundary, asked to be backed by
// huge pages where they cover it, as numpy asks for its large arrays.
Block map_block(std::size_t bytes) {
  void* p = mmap(nullptr, bytes + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t aligned = (start + kHugePage - 1) & ~(kHugePage - 1);
  if (aligned > start) munmap(p, aligned - start);
  if (aligned + bytes < start + bytes + kHugePage)
    munmap(reinterpret_cast<void*>(aligned + bytes), start + kHugePage - aligned);
  madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
  return {reinterpret_cast<void*>(aligned), bytes};
}

// The smallest kept block of bytes up to a quarter more, else a new one.
Block take(std::size_t bytes) {
  {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    std::size_t best = p.count;
    for (std::size_t i = 0; i < p.count; ++i)
      if (p.kept[i].bytes >= bytes && p.kept[i].bytes <= bytes + bytes / 4 &&
          (best == p.count || p.kept[i].bytes < p.kept[best].bytes))
        best = i;
    if (best < p.count) return p.remove(best);
  }
  return map_block(bytes);
}

// The capsule's destructor (the array's base): its block is kept, the oldest beyond kKeptBytes
// unmapped.
void give_back(PyObject* capsule) {
  Block* b = static_cast<Block*>(PyCapsule_GetPointer(capsule, nullptr));
  madvise(b->data, b->bytes, MADV_FREE);
  std::array<Block, kMaxKept> evicted;
  std::size_t n = 0;
  {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.count == kMaxKept) evicted[n++] = p.remove(p.count - 1);
    for (std::size_t k = p.count; k > 0; --k) p.kept[k] = p.kept[k - 1];
    p.kept[0] = *b, ++p.count, p.bytes += b->bytes;
    while (p.bytes > kKeptBytes && p.count > 1) evicted[n++] = p.remove(p.count - 1);
  }
  delete b;
  for (std::size_t i = 0; i < n; ++i) unmap(evicted[i]);
}
}  // namespace

py::array pooled_float64(int ndim, const py::ssize_t* shape, std::size_t bytes) {
  using py::detail::npy_api;
  const npy_api& api = npy_api::get();
  Block* block = new Block(take((bytes + kPage - 1) / kPage * kPage));
  PyObject* capsule = PyCapsule_New(block, nullptr, give_back);
  if (!capsule) {
    unmap(*block);
    delete block;
    throw py::error_already_set();
  }
  auto base = py::reinterpret_steal<py::object>(capsule);  // keeps the block if the array is not made
  PyObject* descr = api.PyArray_DescrFromType_(npy_api::NPY_DOUBLE_);  // the reference is stolen below
  const int flags = npy_api::NPY_ARRAY_C_CONTIGUOUS_ | npy_api::NPY_ARRAY_ALIGNED_ | npy_api::NPY_ARRAY_WRITEABLE_;
  PyObject* a =
      api.PyArray_NewFromDescr_(api.PyArray_Type_, descr, ndim, shape, nullptr, block->data, flags, nullptr);
  if (!a) throw py::error_already_set();
  auto out = py::reinterpret_steal<py::array>(a);
  if (api.PyArray_SetBaseObject_(a, base.release().ptr()) != 0) throw py::error_already_set();
  return out;
}

std::size_t release_output_memory() {
  std::array<Block, kMaxKept> kept;
  std::size_t n, bytes;
  {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    kept = p.kept, n = p.count, bytes = p.bytes;
    p.count = p.bytes = 0;
  }
  for (std::size_t i = 0; i < n; ++i) unmap(kept[i]);
  return bytes;
}
#else
py::array pooled_float64(int ndim, const py::ssize_t* shape, std::size_t) { return numpy_float64(ndim, shape); }
std::size_t release_output_memory() { return 0; }
#endif

void bind_output_pool(py::module_& m) {
  m.def("release_output_memory", &release_output_memory,
        "Gives back to the system the memory robokin keeps of freed outputs, and returns how many\n"
        "bytes that was.\n\n"
        "Outputs of 4 MB or more (a batch's frames, positions, Jacobians) are made in memory robokin\n"
        "maps itself. When one is freed its memory is kept, up to 256 MB of the most recently freed,\n"
        "and the next output of its size (or up to a fifth smaller) is written into it: a loop of\n"
        "batch calls then skips the kernel's page faults and zeroing of a fresh output (1e6 RPR\n"
        "frames on one thread: 24 -> 15 ms here). The kernel may take kept memory back under memory\n"
        "pressure at any time. Linux only; elsewhere numpy allocates every output and this returns 0.");
}

}  // namespace robokin::bind
