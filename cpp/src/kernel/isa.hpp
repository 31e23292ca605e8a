// cpp/src/kernel/: the machine room. Private to the core (no public header includes it); the
// model code (chain.cpp, rrr3*.cpp, ik_closed.cpp) states what to compute, this folder how fast:
// - isa.hpp: which vector ISA this CPU has, detected once per process (detected_isa()), and the
//   one way a hot loop gets builds for several ISAs: an always-inlined body (ROBOKIN_KERNEL)
//   wrapped in functions marked ROBOKIN_TARGET_AVX2 / ROBOKIN_TARGET_AVX512, one picked per call
//   by detected_isa(); model code outside this folder reaches it through run_for_isa() only.
//   Every build runs the same operations in the same order without fused multiply-adds
//   (ROBOKIN_NO_CONTRACT where the ISA has them), so all give the same bits, which the tests
//   compare against single calls and KDL.
// - fast_math*: SLEEF's vectorised sin, cos and atan2 (vmath::), whose AVX2 and AVX-512 loops sit
//   in files of their own, compiled with -mavx2 -mfma / -mavx512f (sleef.h declares those routines
//   only then; CMakeLists.txt sets the flags). Those files include nothing but sleef.h and the
//   loops of an unnamed namespace: an inline function of a shared header (this one's, Eigen's, the
//   standard library's) built there with those flags could stand in for every file's copy.
// - fk_path.hpp, fk_lanes.hpp, fk_batch.cpp: a chain's evaluation path and the lane kernel that runs
//   it on N configurations at once (single calls N = 1, the closed forms' checks 8, batch blocks
//   32), with the batch's per-ISA builds.
// - rrr3_ik_batch.hpp/.cpp: the 3-RRR inverse model over a batch of poses (RRR3::ik_batch's loop),
//   the one file besides SLEEF's built with flags of its own (no errno, no FP traps: CMakeLists.txt).
// - paging.hpp: how a large batch output's pages are faulted in ahead of the stores.
// Why it exists, and what each piece measured: benchmarks/README.md, "Where the time goes".
#pragma once

namespace robokin {

namespace kernel {

// The widest vector ISA the kernels may use, in order: Baseline (x86-64's SSE2, or the only build
// on other processors), Avx2 (AVX2 with FMA), Avx512 (AVX-512F besides).
enum class Isa { Baseline, Avx2, Avx512 };

// What this CPU has, read once per process (thread-safe; no environment override).
inline Isa detected_isa() {
#if defined(__GNUC__) && defined(__x86_64__)
  static const Isa isa = [] {
    __builtin_cpu_init();  // this may run before libgcc's own initialiser (static initialisation)
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return Isa::Baseline;
    return __builtin_cpu_supports("avx512f") ? Isa::Avx512 : Isa::Avx2;
  }();
  return isa;
#else
  return Isa::Baseline;
#endif
}

}  // namespace kernel

}  // namespace robokin

// A kernel body, forced inline into its per-ISA builds (so that each build compiles it for its ISA).
// ROBOKIN_DISPATCH: the per-ISA builds exist (GCC or Clang on x86-64); elsewhere only the baseline.
#if defined(__GNUC__) && defined(__x86_64__)
#define ROBOKIN_DISPATCH 1
#define ROBOKIN_KERNEL inline __attribute__((always_inline))
#define ROBOKIN_TARGET_AVX2 __attribute__((target("avx2")))
#define ROBOKIN_TARGET_AVX512 __attribute__((target("avx512f")))
#define ROBOKIN_NO_CONTRACT __attribute__((optimize("fp-contract=off")))
#else
#define ROBOKIN_KERNEL inline
#endif

namespace robokin::kernel {

#ifdef ROBOKIN_DISPATCH
// Kernel::run built for AVX2 (without FMA: "avx2" alone, so the same bits as the baseline build).
template <class Kernel, class... A>
ROBOKIN_TARGET_AVX2 void run_avx2(A... args) {
  Kernel::run(args...);
}
#endif

// The door of a model file's hot loop: Kernel::run(args...) (a static ROBOKIN_KERNEL function, so
// inlined into each build) run in its AVX2 build where this CPU has AVX2, else in the baseline
// build. Both give the same bits; the AVX2 build takes 4 doubles per vector instead of 2. The
// arguments go by value, pointers and numbers: a number read through a reference could alias the
// loop's outputs, and the vectoriser would then leave the loop scalar. A pointer's __restrict does
// not survive being passed through: a loop whose stores could alias its loads needs `#pragma GCC
// ivdep` (rrr3_ik_batch.cpp's LegArgs), or it stays scalar. A Kernel is file-local (an
// unnamed namespace): its builds then cannot be merged with another file's compiled under other
// flags.
template <class Kernel, class... A>
void run_for_isa(A... args) {
#ifdef ROBOKIN_DISPATCH
  if (detected_isa() != Isa::Baseline) return run_avx2<Kernel>(args...);
#endif
  Kernel::run(args...);
}

}  // namespace robokin::kernel
