// The 3-RRR inverse model over a batch of poses, written for the vectoriser: blocks of poses, one
// branch-free loop per stage (CMakeLists.txt compiles this file without errno and FP traps so the
// loops vectorise). Same bits as RRR3::ik, which uses the same leg_alpha_args and vmath routines.
#include "rrr3_ik_batch.hpp"

#include "fast_math.hpp"
#include "isa.hpp"
#include "../rrr3_leg.hpp"

#include "robokin/parallel.hpp"

#include <algorithm>
#include <limits>

namespace robokin::kernel {

namespace {

constexpr long kBlock = 256;

// The legs' atan2 arguments for one block of poses (a loop the vectoriser takes over contiguous
// arrays; run by kernel::run_for_isa, no FMA in any build, so every build gives RRR3::ik's bits),
// the unreachable rows' ok set to 0.
struct LegArgs {
  static ROBOKIN_KERNEL void run(long nb, const double* __restrict x, const double* __restrict y,
                                 const double* __restrict c, const double* __restrict s, double ox, double oy,
                                 double bx, double by, double m, double l1, double l2, double* __restrict Y,
                                 double* __restrict X, double* __restrict ok) {
    // Each k reads its inputs and writes its outputs only: no dependence between iterations (the
    // pointers' __restrict is not kept through run_for_isa's builds, which take them by value).
#pragma GCC ivdep
    for (long k = 0; k < nb; ++k) {
      const bool reach = leg_alpha_args(x[k], y[k], c[k], s[k], ox, oy, bx, by, m, l1, l2, Y[k], X[k]);
      ok[k] = reach ? ok[k] : 0.0;
    }
  }
};

// One block of poses: SLEEF's sincos of the orientations, the legs' atan2 arguments (LegArgs),
// SLEEF's atan2, the unreachable rows NaN.
void ik_block(const RRR3Legs& legs, const double* p, long nb, double* dst) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double x[kBlock], y[kBlock], phi[kBlock], c[kBlock], s[kBlock], Y[3][kBlock], X[3][kBlock], a[3][kBlock],
      ok[kBlock];
  for (long k = 0; k < nb; ++k) x[k] = p[3 * k], y[k] = p[3 * k + 1], phi[k] = p[3 * k + 2], ok[k] = 1.0;
  vmath::sincos(phi, s, c, nb);
  for (int i = 0; i < 3; ++i)
    run_for_isa<LegArgs>(nb, x, y, c, s, legs.o[2 * i], legs.o[2 * i + 1], legs.b[2 * i], legs.b[2 * i + 1],
                         legs.m[i], legs.l1, legs.l2, Y[i], X[i], ok);
  for (int i = 0; i < 3; ++i) vmath::atan2(Y[i], X[i], a[i], nb);
  for (long k = 0; k < nb; ++k) {
    dst[3 * k] = ok[k] != 0.0 ? a[0][k] : nan;
    dst[3 * k + 1] = ok[k] != 0.0 ? a[1][k] : nan;
    dst[3 * k + 2] = ok[k] != 0.0 ? a[2][k] : nan;
  }
}

}  // namespace

void rrr3_ik_batch(const RRR3Legs& legs, const double* poses, long count, double* out, Progress* progress) {
  parallel_for(count, 8192, [&](long begin, long end) {
    for (long k0 = begin; k0 < end; k0 += kBlock)
      ik_block(legs, poses + 3 * k0, std::min(kBlock, end - k0), out + 3 * k0);
  }, progress);
}

}  // namespace robokin::kernel
