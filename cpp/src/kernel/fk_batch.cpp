// The lane kernel's entry points (fk_path.hpp) and the per-ISA builds of the batch's: the kernel
// (fk_lanes.hpp) is forced inline into its callers, so that the batch loop is compiled three times:
// for the baseline ISA (2 doubles per vector), AVX2 (4) and AVX-512 (8), chosen by detected_isa()
// (isa.hpp). Contraction into fused multiply-adds is turned off in those copies, so they round
// exactly as the baseline: the same results, bit for bit, as single calls.
#include "fk_lanes.hpp"
#include "paging.hpp"

#include "robokin/parallel.hpp"

#include <atomic>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

namespace robokin {

namespace kernel {

namespace {

#ifdef ROBOKIN_DISPATCH
// The same for a whole block, 4 lanes at a time: each row of R and p transposed in registers into
// the 4 lanes' matrix rows, one 32-byte store per row (48 loads and 16 stores of 8 bytes per lane
// before). The same bits, moved.
ROBOKIN_TARGET_AVX2 void block_to_4x4_avx2(const Lanes<kBlock>& L, double* m) {
  static_assert(kBlock % 4 == 0, "whole vectors of lanes");
  const __m256d last = _mm256_set_pd(1.0, 0.0, 0.0, 0.0);
  for (int k = 0; k < kBlock; k += 4, m += 64) {
    for (int r = 0; r < 3; ++r) {
      const __m256d a = _mm256_loadu_pd(L.R[3 * r] + k), b = _mm256_loadu_pd(L.R[3 * r + 1] + k);
      const __m256d c = _mm256_loadu_pd(L.R[3 * r + 2] + k), d = _mm256_loadu_pd(L.p[r] + k);
      const __m256d ab0 = _mm256_unpacklo_pd(a, b), ab1 = _mm256_unpackhi_pd(a, b);  // lanes 0, 2 | 1, 3
      const __m256d cd0 = _mm256_unpacklo_pd(c, d), cd1 = _mm256_unpackhi_pd(c, d);
      _mm256_storeu_pd(m + 4 * r, _mm256_permute2f128_pd(ab0, cd0, 0x20));
      _mm256_storeu_pd(m + 16 + 4 * r, _mm256_permute2f128_pd(ab1, cd1, 0x20));
      _mm256_storeu_pd(m + 32 + 4 * r, _mm256_permute2f128_pd(ab0, cd0, 0x31));
      _mm256_storeu_pd(m + 48 + 4 * r, _mm256_permute2f128_pd(ab1, cd1, 0x31));
    }
    for (int j = 0; j < 4; ++j) _mm256_storeu_pd(m + 16 * j + 12, last);
  }
}
// Pairs of values (128 bits each) gathered from two vectors of four pairs: x's even pairs, then
// y's; x's odd pairs, then y's.
__attribute__((target("avx512f"), always_inline)) inline __m512d even_pairs(__m512d x, __m512d y) {
  return _mm512_shuffle_f64x2(x, y, 0x88);
}
__attribute__((target("avx512f"), always_inline)) inline __m512d odd_pairs(__m512d x, __m512d y) {
  return _mm512_shuffle_f64x2(x, y, 0xdd);
}
// block_to_4x4_avx2 with AVX-512, 8 lanes at a time: lane k's rows 0 and 1 in one 64-byte store,
// rows 2 and 3 in another (an 8 x 8 transpose of R's rows 0, 1 and p's; a 4 x 8 one completed by
// the constant row). The same bits, moved in fewer, wider stores.
ROBOKIN_TARGET_AVX512 void block_to_4x4_avx512(const Lanes<kBlock>& L, double* m) {
  static_assert(kBlock % 8 == 0, "whole vectors of lanes");
  const __m512d row3 = _mm512_set_pd(1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // (0 0 0 1) unpacked, gathered
  const int lane[4] = {0, 2, 1, 3};  // the first lane of the pairs (even, odd) of each vector below
  for (int k = 0; k < kBlock; k += 8, m += 128) {
    // Rows 0 and 1 as (a b) (c d) pairs: lo[r], lo[2 + r] row r of lanes 0 4 and 2 6; hi[r],
    // hi[2 + r] of lanes 1 5 and 3 7.
    __m512d lo[4], hi[4];
    for (int r = 0; r < 3; ++r) {
      const __m512d a = _mm512_loadu_pd(L.R[3 * r] + k), b = _mm512_loadu_pd(L.R[3 * r + 1] + k);
      const __m512d c = _mm512_loadu_pd(L.R[3 * r + 2] + k), d = _mm512_loadu_pd(L.p[r] + k);
      const __m512d ab_even = _mm512_unpacklo_pd(a, b), ab_odd = _mm512_unpackhi_pd(a, b);
      const __m512d cd_even = _mm512_unpacklo_pd(c, d), cd_odd = _mm512_unpackhi_pd(c, d);
      // Row r of lanes 0, 2 | 4, 6 (even pairs) and 1, 3 | 5, 7 (odd).
      if (r < 2) {
        lo[r] = even_pairs(ab_even, cd_even), lo[2 + r] = odd_pairs(ab_even, cd_even);
        hi[r] = even_pairs(ab_odd, cd_odd), hi[2 + r] = odd_pairs(ab_odd, cd_odd);
        continue;
      }
      const __m512d r2[4] = {even_pairs(ab_even, cd_even), odd_pairs(ab_even, cd_even), even_pairs(ab_odd, cd_odd),
                             odd_pairs(ab_odd, cd_odd)};  // lanes 0 4 | 2 6 | 1 5 | 3 7, rows 2 as pairs
      for (int h = 0; h < 4; ++h) {
        _mm512_storeu_pd(m + 16 * lane[h] + 8, even_pairs(r2[h], row3));
        _mm512_storeu_pd(m + 16 * (lane[h] + 4) + 8, odd_pairs(r2[h], row3));
      }
    }
    // Rows 0 and 1: lanes 0 4 (lo[0], lo[1]), 2 6 (lo[2], lo[3]), 1 5 (hi[0], hi[1]), 3 7 (hi[2], hi[3]).
    const __m512d* pairs[4] = {lo, lo + 2, hi, hi + 2};
    for (int h = 0; h < 4; ++h) {
      _mm512_storeu_pd(m + 16 * lane[h], even_pairs(pairs[h][0], pairs[h][1]));
      _mm512_storeu_pd(m + 16 * (lane[h] + 4), odd_pairs(pairs[h][0], pairs[h][1]));
    }
  }
}
// The joint values of a batch block (kBlock configurations of dof joints at q) joint by joint:
// qT[j * kBlock + k] = q[k * dof + j], 8 lanes per gather. Read with a stride of dof, run_lanes
// loaded them one value at a time (the gain is in benchmarks/README.md).
constexpr int kGatherJoints = 16;
ROBOKIN_TARGET_AVX512 void gather_block_avx512(const double* q, int dof, double* qT) {
  const long d = dof;
  for (int k = 0; k < kBlock; k += 8) {
    const __m512i at = _mm512_set_epi64((k + 7) * d, (k + 6) * d, (k + 5) * d, (k + 4) * d, (k + 3) * d,
                                        (k + 2) * d, (k + 1) * d, k * d);
    for (int j = 0; j < dof; ++j) _mm512_storeu_pd(qT + j * kBlock + k, _mm512_i64gather_pd(at, q + j, 8));
  }
}
#endif

// Configurations [begin, end) of a batch, in blocks of kBlock lanes; false when a joint value or a
// result is not finite. With `populate`, the output's pages are faulted in ahead of the stores.
ROBOKIN_KERNEL bool batch_range_kernel(const FkPath& path, const double* q, long begin, long end, double* out,
                                       FkOutput what, bool populate) {
  const int dof = path.dof();
  const long width = what == FkOutput::Position ? 3 : 16;
  Lanes<kBlock> L;
  bool finite = true;
  long b = begin, populated = begin;
  auto fault_in = [&](long upto) {
    if (!populate || upto <= populated) return;
    const long to = kernel::next_page_end(out, width, upto, end);
    kernel::populate_for_writing(out + width * populated, out + width * to);
    populated = to;
  };
#ifdef ROBOKIN_DISPATCH
  // A batch block's joint values gathered joint by joint and its frames stored with AVX-512 or AVX2
  // where the CPU has them; else plain loads and stores.
  const Isa isa = detected_isa();
  const bool gather = isa == Isa::Avx512 && dof <= kGatherJoints;
  alignas(64) double qT[kGatherJoints * kBlock];
#endif
  for (; b + kBlock <= end; b += kBlock) {
    const double* qb = q + b * dof;
    const double* lanes_q = qb;  // the block's joint values as run_lanes reads them
    long lanes_stride = dof;
#ifdef ROBOKIN_DISPATCH
    if (gather) {
      gather_block_avx512(qb, dof, qT);
      lanes_q = qT, lanes_stride = kJointMajor;
    }
#endif
    if (populate) {
      // The next block's output lines fetched while this one is computed: the kernel's zeroing
      // leaves them out of the first-level caches, and each store waited for its line. A part is
      // asked for before the chain and a part after each joint: all at once, the requests beyond
      // the cache's few outstanding misses stalled the block; two blocks ahead measured slower.
      // Written here, not in a helper: GCC deletes calls to a function whose only effect is a prefetch.
      const long next_end = std::min(end, b + 2 * kBlock);
      fault_in(next_end);
      const char* line = reinterpret_cast<const char*>(out + width * (b + kBlock));
      const char* const stop = reinterpret_cast<const char*>(out + width * next_end);
      const long part = ((stop - line) / 64 / (dof + 1) + 1) * 64;  // bytes of lines per part
      auto fetch_part = [&](int /*joint*/) {
        for (const char* e = std::min(stop, line + part); line < e; line += 64) __builtin_prefetch(line, 1, 3);
      };
      fetch_part(-1);  // before the first joint
      run_lanes<kBlock>(path, L, lanes_q, lanes_stride, nullptr, fetch_part);
    } else {
      run_lanes<kBlock>(path, L, lanes_q, lanes_stride, nullptr);
    }
    finite &= values_finite(qb, kBlock * dof) & lanes_finite(L, kBlock);
    fault_in(b + kBlock);
#ifdef ROBOKIN_DISPATCH
    if (what == FkOutput::Frame && isa != Isa::Baseline) {
      if (isa == Isa::Avx512) block_to_4x4_avx512(L, out + width * b);
      else block_to_4x4_avx2(L, out + width * b);
      continue;
    }
#endif
    lanes_store(L, kBlock, what, out + width * b);
  }
  // The tail, one configuration at a time (the same operations as a block lane).
  Lanes<1> one;
  for (; b < end; ++b) {
    run_lanes<1>(path, one, q + b * dof, 0, nullptr);
    finite &= values_finite(q + b * dof, dof) & lanes_finite(one, 1);
    fault_in(b + 1);
    lanes_store(one, 1, what, out + width * b);
  }
  return finite;
}

bool batch_range(const FkPath& path, const double* q, long begin, long end, double* out, FkOutput what,
                 bool populate) {
  return batch_range_kernel(path, q, begin, end, out, what, populate);
}

#ifdef ROBOKIN_DISPATCH
ROBOKIN_TARGET_AVX2 ROBOKIN_NO_CONTRACT bool batch_range_avx2(const FkPath& path, const double* q, long begin, long end,
                                                         double* out, FkOutput what, bool populate) {
  return batch_range_kernel(path, q, begin, end, out, what, populate);
}

ROBOKIN_TARGET_AVX512 ROBOKIN_NO_CONTRACT bool batch_range_avx512(const FkPath& path, const double* q, long begin, long end,
                                                             double* out, FkOutput what, bool populate) {
  return batch_range_kernel(path, q, begin, end, out, what, populate);
}
#endif

constexpr int kFkFewJoints = 32;

// Every lane is evaluated: the unused ones repeat the first configuration.
ROBOKIN_KERNEL void fk_few_kernel(const FkPath& path, const double* q, int count, Rigid* out) {
  const int dof = path.dof();
  double padded[Chain::kFkFew * kFkFewJoints];
  std::copy(q, q + count * dof, padded);
  for (int k = count; k < Chain::kFkFew; ++k) std::copy(q, q + dof, padded + k * dof);
  Lanes<Chain::kFkFew> L;
  run_lanes<Chain::kFkFew>(path, L, padded, dof, nullptr);
  for (int k = 0; k < count; ++k) lane_to_rigid(L, k, out[k]);
}

// The same from the joints' turns (rows of dof cosines and sines, as q's), gathered joint by joint.
ROBOKIN_KERNEL void fk_few_turns_kernel(const FkPath& path, const double* c, const double* s, int count, Rigid* out) {
  constexpr int N = Chain::kFkFew;
  const int dof = path.dof();
  double turns[2 * N * kFkFewJoints];
  for (int j = 0; j < dof; ++j)
    for (int k = 0; k < N; ++k) {
      const int from = (k < count ? k : 0) * dof + j;
      turns[j * N + k] = c[from], turns[(dof + j) * N + k] = s[from];
    }
  Lanes<N> L;
  run_lanes<N>(path, L, nullptr, 0, nullptr, {}, turns);
  for (int k = 0; k < count; ++k) lane_to_rigid(L, k, out[k]);
}

void fk_few_lanes(const FkPath& path, const double* q, int count, Rigid* out) {
  fk_few_kernel(path, q, count, out);
}

void fk_few_turns_lanes(const FkPath& path, const double* c, const double* s, int count, Rigid* out) {
  fk_few_turns_kernel(path, c, s, count, out);
}

#ifdef ROBOKIN_DISPATCH
ROBOKIN_TARGET_AVX2 ROBOKIN_NO_CONTRACT void fk_few_avx2(const FkPath& path, const double* q, int count, Rigid* out) {
  fk_few_kernel(path, q, count, out);
}

ROBOKIN_TARGET_AVX2 ROBOKIN_NO_CONTRACT void fk_few_turns_avx2(const FkPath& path, const double* c, const double* s,
                                                               int count, Rigid* out) {
  fk_few_turns_kernel(path, c, s, count, out);
}
#endif

}  // namespace

void fk_few(const FkPath& path, const double* q, int count, Rigid* out) {
  const int dof = path.dof();
  if (count > Chain::kFkFew || dof > kFkFewJoints) {  // not for this kernel: one at a time
    for (int k = 0; k < count; ++k) fk(path, q + k * dof, out[k]);
    return;
  }
  if (count <= 0) return;
#ifdef ROBOKIN_DISPATCH
  // AVX2 (4 lanes per vector) measured faster than the baseline's 2 for a UR closed-form call; an
  // AVX-512 build of the same kernel did not, so none is made (benchmarks/README.md).
  if (detected_isa() != Isa::Baseline) return fk_few_avx2(path, q, count, out);
#endif
  fk_few_lanes(path, q, count, out);
}

void fk_few_turns(const FkPath& path, const double* q, const double* c, const double* s, int count, Rigid* out) {
  if (count > Chain::kFkFew || path.dof() > kFkFewJoints || !path.turns) return fk_few(path, q, count, out);
  if (count <= 0) return;
#ifdef ROBOKIN_DISPATCH
  if (detected_isa() != Isa::Baseline) return fk_few_turns_avx2(path, c, s, count, out);
#endif
  fk_few_turns_lanes(path, c, s, count, out);
}

bool fk_batch(const FkPath& path, const double* q, long count, double* out, FkOutput what, Progress* progress) {
  // A large frame output (beyond the caches) is faulted in chunk by chunk as it is written.
  const bool populate = what == FkOutput::Frame && count >= 32768;
#ifdef ROBOKIN_DISPATCH
  const Isa isa = detected_isa();
#endif
  std::atomic<bool> finite{true};
  parallel_for(count, 20000, [&](long begin, long end) {
    bool ok;
#ifdef ROBOKIN_DISPATCH
    if (isa == Isa::Avx512) ok = batch_range_avx512(path, q, begin, end, out, what, populate);
    else if (isa == Isa::Avx2) ok = batch_range_avx2(path, q, begin, end, out, what, populate);
    else ok = batch_range(path, q, begin, end, out, what, populate);
#else
    ok = batch_range(path, q, begin, end, out, what, populate);
#endif
    if (!ok) finite = false;
  }, progress);
  return finite;
}

}  // namespace kernel

}  // namespace robokin
