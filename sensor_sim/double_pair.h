// Two doubles computed together: the two sensitive axes (x_C, y_C) of one ADXL210E chip go through
// the same per-frame arithmetic, so they share each instruction (a GCC/Clang vector extension; on
// x86-64 one SSE2 packed instruction per operation). Each lane rounds exactly as the scalar
// operation would (IEEE 754 per element, and without -ffast-math or FMA no contraction), so a
// computation on pairs gives bit for bit the scalar results.
//
// Only what the chip step needs: element-wise + − × ÷ and comparisons come with the type; the
// functions below add what it lacks (floor, square root, exp per lane). Lanes are read with p[0],
// p[1] and built with DoublePair{a, b}.
#pragma once

#include <cmath>

#include "sensor_sim/fast_math.h"

namespace adahrs::sensor_sim {

using DoublePair = double __attribute__((vector_size(2 * sizeof(double))));

/// floor of each lane, exact for |x| < 2^51 (RoundHalfEven, then one down where that rounded up).
inline DoublePair FloorPair(DoublePair x) {
  const DoublePair shift = {fast_math_internal::kRoundShift, fast_math_internal::kRoundShift};
  const DoublePair nearest = (x + shift) - shift;
  return nearest > x ? nearest - 1.0 : nearest;
}

/// std::sqrt of each lane (correctly rounded, as the scalar function).
inline DoublePair SqrtPair(DoublePair x) { return DoublePair{std::sqrt(x[0]), std::sqrt(x[1])}; }

/// BoundedExp of each lane (fast_math.h: within 1 ulp of std::exp on its range).
inline DoublePair BoundedExpPair(DoublePair x) {
  return DoublePair{BoundedExp(x[0]), BoundedExp(x[1])};
}

/// std::clamp(x, lo, hi) of each lane (a NaN lane stays NaN, as with std::clamp).
inline DoublePair ClampPair(DoublePair x, double lo, double hi) {
  const DoublePair lo_pair = {lo, lo};
  const DoublePair hi_pair = {hi, hi};
  return x < lo_pair ? lo_pair : (hi_pair < x ? hi_pair : x);
}

}  // namespace adahrs::sensor_sim
