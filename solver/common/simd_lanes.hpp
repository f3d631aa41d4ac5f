// W elements in the W lanes of one vector (GCC vector extensions): the
// element kernels (hex8.hpp, quad4_axisym.hpp) are templates on the number
// type T, double for one element and Lane<W> for W at once, lane by lane the
// same IEEE operations (the build has -ffp-contract=off, so no lane fuses a
// multiply-add the scalar code does not), hence the same results to the bit.
// The loops that use them (solver/fe/fe_block_lanes.hpp,
// solver/material/update_points_isa.cpp) are compiled once per instruction
// set and chosen at run time (solver/common/isa.hpp), so the vectors map onto
// SSE2, AVX2 or AVX-512 registers; nothing here names an instruction set.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

// Kernels that run on lanes are forced inline into those loops: a call would
// pass the vectors through memory, and an out-of-line copy of a template
// could be linked in from another instruction set's object (the test
// build.isa_objects_self_contained).
#define SPLAT_LANE_INLINE [[gnu::always_inline]] inline
// The same for a lambda that takes or returns lane vectors, written after its
// parameter list: GCC does not always inline a lambda passed down through
// for_each_point_field (the test build.lane_kernels_inlined finds any such
// function left out of line).
#define SPLAT_LANE_LAMBDA __attribute__((always_inline))

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

// f applied to each lane of a: each lane rounds as the scalar call does
// (GCC makes one vector instruction of it where it can, as for sqrt).
template <class V, class F>
requires is_lane<V> SPLAT_LANE_INLINE V lane_map(const V& a, F f) {
  V r;
  for (int l = 0; l < static_cast<int>(sizeof(V) / sizeof(double)); ++l) r[l] = f(a[l]);
  return r;
}

inline double lane_sqrt(double a) {
  return std::sqrt(a);
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_sqrt(const V& a) {
  return lane_map(a, [](double x) { return std::sqrt(x); });
}

// The comparison result of T: bool for a double, a vector of 64-bit integers
// (0 or -1 per lane) for a lane vector. `c ? a : b`, `&&`, `||` and `!` work
// on both alike.
template <class T>
using LaneMask = decltype(T{} < T{});

// Whether any lane of a mask is set.
inline bool lane_any(bool m) {
  return m;
}
template <class M>
requires(!std::is_same_v<M, bool>) SPLAT_LANE_INLINE bool lane_any(const M& m) {
  // OR-reduction by halving (log2 W shuffles instead of W lane tests).
  constexpr int W = static_cast<int>(sizeof(M) / sizeof(m[0]));
  M r = m;
  if constexpr (W == 8) {
    r |= __builtin_shuffle(r, M{4, 5, 6, 7, 0, 1, 2, 3});
    r |= __builtin_shuffle(r, M{2, 3, 0, 1, 2, 3, 0, 1});
    r |= __builtin_shuffle(r, M{1, 0, 1, 0, 1, 0, 1, 0});
  } else if constexpr (W == 4) {
    r |= __builtin_shuffle(r, M{2, 3, 0, 1});
    r |= __builtin_shuffle(r, M{1, 0, 1, 0});
  } else {
    static_assert(W == 2);
    r |= __builtin_shuffle(r, M{1, 0});
  }
  return r[0] != 0;
}

// |a| lane by lane (clears the sign bit, as std::abs does).
inline double lane_abs(double a) {
  return std::abs(a);
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_abs(const V& a) {
  return a < V{} ? -a : a + 0.0;  // -0 + 0 = +0, as std::abs(-0)
}

// ln(1 + r) for |r| <= 1/16 by the series 2 (z + z^3/3 + ... + z^11/11),
// z = r / (2 + r) (|z| <= 1/31): its remainder is below 1e-18 of the result,
// and its rounding within 1e-15 of it; `ok` marks |r| <= 1/16. No libm call.
template <class V>
SPLAT_LANE_INLINE V log1p_series(const V& r, LaneMask<V>& ok) {
  ok = lane_abs(r) <= 0.0625;
  const V z = r / (2.0 + r);
  const V z2 = z * z, z4 = z2 * z2;
  const V q0 = 1.0 + z2 * (1.0 / 3.0), q2 = (1.0 / 5.0) + z2 * (1.0 / 7.0),
          q4 = (1.0 / 9.0) + z2 * (1.0 / 11.0);
  return 2.0 * z * ((q0 + q2 * z4) + q4 * (z4 * z4));
}

// ln(a) to 1e-15 (relative), the same value in scalars and in lanes: by
// log1p_series where |a - 1| <= 1/16 (the volume ratios of nearly every
// step), by std::log elsewhere.
inline double lane_log(double a) {
  bool near = false;
  const double series = log1p_series(a - 1.0, near);
  return near ? series : std::log(a);
}
template <class V>
requires is_lane<V> SPLAT_LANE_INLINE V lane_log(const V& a) {
  LaneMask<V> near;
  const V series = log1p_series(a - 1.0, near);
  if (!lane_any(!near)) return series;
  return near ? series : lane_map(a, [](double x) { return std::log(x); });
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

// hughes_winget_rotation and rotate_symmetric (fe_body.hpp), same arithmetic,
// in scalars or lanes, for the FE element loop and the SPH material blocks:
// Eigen's comma initialiser and 3x3 products mixed scalar stores with packet
// loads of the same memory in the element loop (store-forwarding stalls).
// (w21, w02, w10) are W(2,1), W(0,2), W(1,0).
template <class T>
SPLAT_LANE_INLINE void hughes_winget_rotation_cm(const T& w21, const T& w02, const T& w10,
                                                 double dt, T Q[3][3]) {
  const double h = 0.5 * dt;
  const T a0 = h * w21, a1 = h * w02, a2 = h * w10;
  const T a_sq = a0 * a0 + a1 * a1 + a2 * a2;
  const T c = 2.0 / (1.0 + a_sq);
  const T d = 1.0 - c * a_sq;
  Q[0][0] = d + c * a0 * a0, Q[0][1] = c * (a0 * a1 - a2), Q[0][2] = c * (a0 * a2 + a1);
  Q[1][0] = c * (a0 * a1 + a2), Q[1][1] = d + c * a1 * a1, Q[1][2] = c * (a1 * a2 - a0);
  Q[2][0] = c * (a0 * a2 - a1), Q[2][1] = c * (a1 * a2 + a0), Q[2][2] = d + c * a2 * a2;
}

// S <- Q S Q^T for a symmetric S (the six distinct entries, exactly symmetric).
template <class T>
SPLAT_LANE_INLINE void rotate_symmetric_cm(const T Q[3][3], T S[3][3]) {
  T M[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) M[i][k] = Q[i][0] * S[0][k] + Q[i][1] * S[1][k] + Q[i][2] * S[2][k];
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      const T r = M[i][0] * Q[j][0] + M[i][1] * Q[j][1] + M[i][2] * Q[j][2];
      S[i][j] = r;
      S[j][i] = r;
    }
  }
}

}  // namespace splat
