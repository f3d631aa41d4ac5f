// Two elements in one SSE2 register: the element kernels (hex8.hpp,
// quad4_axisym.hpp) are templates on the number type T, double for one
// element and Pair for two at once, lane by lane the same operations, so the
// same results to the bit. SSE2 is part of the x86-64 baseline (no -march).
#pragma once

#include <emmintrin.h>

#include <algorithm>
#include <cmath>

namespace splat {

using Pair = double __attribute__((vector_size(16)));  // lanes 0 and 1

inline Pair make_pair(double lane0, double lane1) {
  return _mm_set_pd(lane1, lane0);
}

// std::max(a, b) lane by lane (a where b is NaN).
inline double lane_max(double a, double b) {
  return std::max(a, b);
}
inline Pair lane_max(Pair a, Pair b) {
  return _mm_max_pd(b, a);
}

inline double lane_sqrt(double a) {
  return std::sqrt(a);
}
inline Pair lane_sqrt(Pair a) {
  return _mm_sqrt_pd(a);
}

// cond > 0 ? value : 0, lane by lane.
inline double lane_if_positive(double cond, double value) {
  return cond > 0.0 ? value : 0.0;
}
inline Pair lane_if_positive(Pair cond, Pair value) {
  return _mm_and_pd(_mm_cmpgt_pd(cond, Pair{}), value);
}

// cond != 0 ? value : 0, lane by lane.
inline double lane_if_nonzero(double cond, double value) {
  return cond != 0.0 ? value : 0.0;
}
inline Pair lane_if_nonzero(Pair cond, Pair value) {
  return _mm_and_pd(_mm_cmpneq_pd(cond, Pair{}), value);
}

}  // namespace splat
