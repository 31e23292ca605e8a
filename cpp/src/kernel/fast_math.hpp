// Vectorised elementary functions over arrays, from SLEEF (Debian's libsleef-dev; fast_math.cpp):
// its 1.0-ulp sincos and atan2 (the "u10" routines: at most 1.0 ulp from the exact result, any
// argument, NaN in -> NaN out), on the widest vector ISA this CPU has (AVX2 with FMA, and AVX-512
// for arrays of 32 values or more where the CPU has it; else SSE2), chosen once per process. The
// AVX2 and AVX-512 routines are SLEEF's deterministic ones ("finz": the same bits on every ISA
// with FMA), and every value goes through the same routine whatever its place in the array (tails
// are padded), so a value gives the same bits in a batch as alone: single calls and batch calls
// agree bit for bit.
#pragma once

namespace robokin {

namespace vmath {

// s[k] = sin x[k], c[k] = cos x[k] for k < n.
void sincos(const double* x, double* s, double* c, long n);

// out[k] = atan2(y[k], x[k]) for k < n.
void atan2(const double* y, const double* x, double* out, long n);

}  // namespace vmath

}  // namespace robokin
