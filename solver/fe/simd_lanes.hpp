// W elements in the W lanes of one vector (GCC vector extensions): the
// element kernels (hex8.hpp, quad4_axisym.hpp) are templates on the number
// type T, double for one element and Lane<W> for W at once, lane by lane the
// same IEEE operations (the build has -ffp-contract=off, so no lane fuses a
// multiply-add the scalar code does not), hence the same results to the bit.
// The loops that use them (fe_body.cpp) are compiled with target_clones, so
// the vectors map onto SSE2, AVX2 or AVX-512 registers chosen at run time;
// nothing here names an instruction set.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

// Kernels that run on lanes are forced inline, so that inside a
// target_clones loop they are compiled for that loop's instruction set
// (a call would run the baseline version).
#define SPLAT_LANE_INLINE [[gnu::always_inline]] inline

namespace splat {

using Lane2 = double __attribute__((vector_size(16)));
using Lane4 = double __attribute__((vector_size(32)));
using Lane8 = double __attribute__((vector_size(64)));
template <int W>
struct LaneType;
template <>
struct LaneType<2> {
  using type = Lane2;
};
template <>
struct LaneType<4> {
  using type = Lane4;
};
template <>
struct LaneType<8> {
  using type = Lane8;
};
template <int W>
using Lane = typename LaneType<W>::type;

template <class T>
inline constexpr bool is_lane = !std::is_same_v<T, double>;

// std::max(a, b) lane by lane (a where b is NaN).
inline double lane_max(double a, double b) {
  return std::max(a, b);
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_max(const V& a, const V& b) {
  return a < b ? b : a;
}

inline double lane_sqrt(double a) {
  return std::sqrt(a);
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_sqrt(const V& a) {
  V r;
  for (int l = 0; l < static_cast<int>(sizeof(V) / sizeof(double)); ++l) r[l] = std::sqrt(a[l]);
  return r;
}

// cond > 0 ? value : 0, lane by lane.
inline double lane_if_positive(double cond, double value) {
  return cond > 0.0 ? value : 0.0;
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_if_positive(const V& cond, const V& value) {
  return cond > V{} ? value : V{};
}

// cond != 0 ? value : 0, lane by lane.
inline double lane_if_nonzero(double cond, double value) {
  return cond != 0.0 ? value : 0.0;
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_if_nonzero(const V& cond, const V& value) {
  return cond != V{} ? value : V{};
}

}  // namespace splat
