// 3-RRR inverse model over a batch of poses, written for the vectoriser: blocks of poses, one
// branch-free loop per stage (CMakeLists.txt compiles this file without errno and FP traps so the
// loops vectorise). Same bits as RRR3::ik, which uses the same leg_alpha.
#include "robokin/parallel.hpp"
#include "robokin/rrr3.hpp"

#include "rrr3_leg.hpp"

#include <cmath>
#include <limits>

namespace robokin {

namespace {

constexpr long kBlock = 256;

// One block of poses. Cloned for AVX2 (4 doubles per vector instead of SSE2's 2) and picked at
// load time; no FMA in either clone, so both give RRR3::ik's bits.
__attribute__((target_clones("avx2", "default"))) void ik_block(const double* p, long nb, const double* o,
                                                                 const double* b, const double* m, double l1,
                                                                 double l2, double* dst) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double c[kBlock], s[kBlock], a[3][kBlock];
  for (long k = 0; k < nb; ++k) simd::sincos(p[3 * k + 2], s[k], c[k]);
  for (int i = 0; i < 3; ++i)
    for (long k = 0; k < nb; ++k)
      a[i][k] = leg_alpha(p[3 * k], p[3 * k + 1], c[k], s[k], o[2 * i], o[2 * i + 1], b[2 * i], b[2 * i + 1], m[i], l1, l2);
  for (long k = 0; k < nb; ++k) {
    const bool ok = !(std::isnan(a[0][k]) | std::isnan(a[1][k]) | std::isnan(a[2][k]));
    dst[3 * k] = ok ? a[0][k] : nan;
    dst[3 * k + 1] = ok ? a[1][k] : nan;
    dst[3 * k + 2] = ok ? a[2][k] : nan;
  }
}

}  // namespace

void RRR3::ik_batch(const double* poses, long count, const Mode& mode, double* out, Progress* progress) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double o[6], b[6], m[3];
  for (int i = 0; i < 3; ++i) o[2 * i] = o_[i].x(), o[2 * i + 1] = o_[i].y(), b[2 * i] = b_[i].x(), b[2 * i + 1] = b_[i].y(), m[i] = mode[i];
  parallel_for(count, 8192, [&](long begin, long end) {
    for (long k0 = begin; k0 < end; k0 += kBlock) {
      const long nb = std::min(kBlock, end - k0);
      const double* p = poses + 3 * k0;
      double* dst = out + 3 * k0;
      ik_block(p, nb, o, b, m, l1_, l2_, dst);
      // Huge orientations: the series' range reduction is not exact there, use the scalar path.
      for (long k = 0; k < nb; ++k)
        if (!simd::sincos_in_range(p[3 * k + 2]) && ik(Pose(p[3 * k], p[3 * k + 1], p[3 * k + 2]), mode, dst + 3 * k) >= 0)
          dst[3 * k] = dst[3 * k + 1] = dst[3 * k + 2] = nan;
    }
  }, progress);
}

}  // namespace robokin
