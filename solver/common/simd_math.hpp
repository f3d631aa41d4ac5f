// exp, log and pow written once as templates on the number type T: double, or
// a GCC vector of doubles (double __attribute__((vector_size(32 or 64)))), so
// that a loop over material points run in SIMD lanes and the scalar code for
// one point do the same IEEE operations in the same order and give the same
// bits in every lane (the build has -ffp-contract=off: no fused multiply-adds).
//
// Branch-free: range reduction with integer bit manipulation, a polynomial,
// and selects for the special values. Coefficients are Taylor coefficients
// (1/k! and 2/(2k+1)), evaluated by Estrin's scheme, enough terms for the truncation to stay below
// 2^-56.
//   exp(x) = 2^k e^r,  k = round(x / ln 2),  r = x - k ln 2 (two-part ln 2),
//            |r| <= ln 2 / 2, e^r = 1 + (r + r^2 (1/2! + r/3! + ... + r^11/13!));
//            2^k applied as two exact powers of two so that a subnormal result
//            is rounded once. Error below 1 ulp (0.97 ulp the largest seen over
//            2e6 random arguments; the test asserts 1.5).
//            exp(NaN) = NaN, exp(+inf) = +inf, exp(-inf) = +0, overflow for
//            x > 709.78 gives +inf, underflow below -745.13 gives +0.
//   log(x) = k ln 2 + log(1 + f),  x = 2^k (1 + f),  sqrt(2)/2 <= 1 + f < sqrt(2),
//            log(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2)),  s = f / (2 + f),
//            R(z) = sum_{j=1..11} 2 z^j / (2j + 1) (the series of
//            log((1 + s) / (1 - s)) - 2 s over s); subnormals are scaled by 2^54
//            first. Error below 1 ulp (0.71 seen; 1.5 asserted). log(+0) = log(-0) = -inf, log(x <
//            0) = NaN, log(+inf) = +inf, log(NaN) = NaN.
//   pow(x, y) = exp(y log(x)) for x > 0 (the relative error grows with
//            |y log x|, as for any exp-log power; fine for the exponents of the
//            material laws, n and m of order 1).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

// The vector types are only passed between always_inline functions: the ABI
// note GCC gives for them does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace splat::simd {

using v4d = double __attribute__((vector_size(32)));
using v4l = std::int64_t __attribute__((vector_size(32)));
using v8d = double __attribute__((vector_size(64)));
using v8l = std::int64_t __attribute__((vector_size(64)));

// The integer type of the same width as T (and the type of T's comparisons
// for the vector types).
template <class T>
struct int_of;
template <>
struct int_of<double> {
  using type = std::int64_t;
};
template <>
struct int_of<v4d> {
  using type = v4l;
};
template <>
struct int_of<v8d> {
  using type = v8l;
};

template <class T>
using int_t = typename int_of<T>::type;

// The type of a comparison of two T: bool for double, int_t<T> (0 or -1 per
// lane) for the vectors.
template <class T>
using mask_t = std::conditional_t<std::is_same_v<T, double>, bool, int_t<T>>;

template <class T>
inline constexpr int lanes = static_cast<int>(sizeof(T) / sizeof(double));

// c in every lane (c - 0 keeps -0 and NaN as they are).
template <class T>
[[gnu::always_inline]] inline T broadcast(double c) {
  if constexpr (std::is_same_v<T, double>) {
    return c;
  } else {
    return c - T{};
  }
}

template <class T>
[[gnu::always_inline]] inline int_t<T> broadcast_int(std::int64_t c) {
  if constexpr (std::is_same_v<T, double>) {
    return c;
  } else {
    return c - int_t<T>{};
  }
}

template <class T>
[[gnu::always_inline]] inline int_t<T> as_int(T x) {
  return std::bit_cast<int_t<T>>(x);
}

template <class T>
[[gnu::always_inline]] inline T as_double(int_t<T> i) {
  if constexpr (std::is_same_v<T, double>) {
    return std::bit_cast<double>(i);
  } else {
    return std::bit_cast<T>(i);
  }
}

// m ? a : b per lane.
template <class T>
[[gnu::always_inline]] inline T select(mask_t<T> m, T a, T b) {
  return m ? a : b;
}
template <class T>
[[gnu::always_inline]] inline int_t<T> select_int(mask_t<T> m, int_t<T> a, int_t<T> b) {
  return m ? a : b;
}

// Mask logic that reads the same for bool and for vector masks.
template <class M>
[[gnu::always_inline]] inline M mask_and(M a, M b) {
  if constexpr (std::is_same_v<M, bool>) {
    return a && b;
  } else {
    return a & b;
  }
}
template <class M>
[[gnu::always_inline]] inline M mask_or(M a, M b) {
  if constexpr (std::is_same_v<M, bool>) {
    return a || b;
  } else {
    return a | b;
  }
}
template <class M>
[[gnu::always_inline]] inline M mask_not(M a) {
  if constexpr (std::is_same_v<M, bool>) {
    return !a;
  } else {
    return ~a;
  }
}
template <class M>
[[gnu::always_inline]] inline bool any(M a) {
  if constexpr (std::is_same_v<M, bool>) {
    return a;
  } else {
    bool r = false;
    for (int l = 0; l < static_cast<int>(sizeof(M) / sizeof(std::int64_t)); ++l) r |= a[l] != 0;
    return r;
  }
}

// |x| (clears the sign bit, as std::abs does).
template <class T>
[[gnu::always_inline]] inline T abs(T x) {
  return as_double<T>(as_int(x) & broadcast_int<T>(0x7fffffffffffffffLL));
}

// std::max(a, b) and std::min(a, b), with their NaN behaviour: (a < b) ? b : a
// and (b < a) ? b : a.
template <class T>
[[gnu::always_inline]] inline T max(T a, T b) {
  return select<T>(a < b, b, a);
}
template <class T>
[[gnu::always_inline]] inline T min(T a, T b) {
  return select<T>(b < a, b, a);
}

template <class T>
[[gnu::always_inline]] inline T sqrt(T x) {
  if constexpr (std::is_same_v<T, double>) {
    return std::sqrt(x);
  } else {
    T r = x;
    for (int l = 0; l < lanes<T>; ++l) r[l] = __builtin_sqrt(x[l]);
    return r;
  }
}

namespace detail {
// ln 2 = ln2_hi + ln2_lo, ln2_hi with 40 significant bits so that k ln2_hi is
// exact for |k| < 2^13.
inline constexpr double ln2_hi = 0x1.62e42fefa2000p-1;
inline constexpr double ln2_lo = 0x1.9ef35793c7673p-41;
inline constexpr double log2_e = 0x1.71547652b82fep+0;
inline constexpr double sqrt2 = 0x1.6a09e667f3bcdp+0;
inline constexpr double round_magic = 0x1.8p52;  // adding it rounds to an integer
}  // namespace detail

template <class T>
[[gnu::always_inline]] inline T exp(T x) {
  using namespace detail;
  // Clamp so that k stays small (the result over- or underflows anyway); NaN
  // passes (its comparisons are false) and stays NaN through r.
  T xc = select<T>(x > broadcast<T>(710.0), broadcast<T>(710.0), x);
  xc = select<T>(xc < broadcast<T>(-746.0), broadcast<T>(-746.0), xc);
  const T t = xc * log2_e + round_magic;
  const T kd = t - round_magic;
  const int_t<T> k = as_int(t) - broadcast_int<T>(std::bit_cast<std::int64_t>(round_magic));
  const T r = (xc - kd * ln2_hi) - kd * ln2_lo;
  // q = sum_{j=0..11} r^j / (j + 2)!, by Estrin's scheme (a short
  // dependency chain: this sits on the critical path of the material update).
  const T r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const T p0 = 0.5 + r * (1.0 / 6.0);
  const T p1 = (1.0 / 24.0) + r * (1.0 / 120.0);
  const T p2 = (1.0 / 720.0) + r * (1.0 / 5040.0);
  const T p3 = (1.0 / 40320.0) + r * (1.0 / 362880.0);
  const T p4 = (1.0 / 3628800.0) + r * (1.0 / 39916800.0);
  const T p5 = (1.0 / 479001600.0) + r * (1.0 / 6227020800.0);
  const T q = ((p0 + r2 * p1) + r4 * (p2 + r2 * p3)) + r8 * (p4 + r2 * p5);
  const T y = 1.0 + (r + r2 * q);
  // 2^k = 2^k1 2^k2 with both factors normal: y 2^k1 is exact, the second
  // product rounds once (into the subnormals if it must).
  const int_t<T> k1 = k >> 1;
  const int_t<T> k2 = k - k1;
  const T two_k1 = as_double<T>((k1 + 1023) << 52);
  const T two_k2 = as_double<T>((k2 + 1023) << 52);
  return (y * two_k1) * two_k2;
}

template <class T>
[[gnu::always_inline]] inline T log(T x) {
  using namespace detail;
  const mask_t<T> sub = x < broadcast<T>(0x1p-1022);
  const T xs = select<T>(sub, x * 0x1p54, x);
  const int_t<T> ix = as_int(xs);
  int_t<T> k =
      ((ix >> 52) & 0x7ff) - 1023 - select_int<T>(sub, broadcast_int<T>(54), broadcast_int<T>(0));
  T m = as_double<T>((ix & 0x000fffffffffffffLL) | 0x3ff0000000000000LL);  // [1, 2)
  const mask_t<T> big = m > broadcast<T>(sqrt2);
  m = select<T>(big, m * 0.5, m);  // [sqrt(2)/2, sqrt(2))
  k = k + select_int<T>(big, broadcast_int<T>(1), broadcast_int<T>(0));
  const T f = m - 1.0;
  const T s = f / (2.0 + f);
  const T z = s * s;
  // R = z sum_{j=0..10} 2 z^j / (2j + 3), by Estrin's scheme.
  const T z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const T a0 = (2.0 / 3.0) + z * (2.0 / 5.0);
  const T a1 = (2.0 / 7.0) + z * (2.0 / 9.0);
  const T a2 = (2.0 / 11.0) + z * (2.0 / 13.0);
  const T a3 = (2.0 / 15.0) + z * (2.0 / 17.0);
  const T a4 = (2.0 / 19.0) + z * (2.0 / 21.0);
  const T R = z * (((a0 + z2 * a1) + z4 * (a2 + z2 * a3)) + z8 * (a4 + z2 * (2.0 / 23.0)));
  const T hfsq = 0.5 * f * f;
  // k as a double without an int64 -> double conversion (none in AVX2).
  const T dk =
      as_double<T>(k + broadcast_int<T>(std::bit_cast<std::int64_t>(round_magic))) - round_magic;
  const T y = (((s * (hfsq + R) + dk * ln2_lo) - hfsq) + f) + dk * ln2_hi;
  const T inf = broadcast<T>(HUGE_VAL);
  const T special = select<T>(x == broadcast<T>(0.0), -inf,
                              select<T>(x < broadcast<T>(0.0), broadcast<T>(NAN), x));
  return select<T>(mask_and(x > broadcast<T>(0.0), x < inf), y, special);
}

template <class T>
[[gnu::always_inline]] inline T pow(T x, T y) {
  return simd::exp(y * simd::log(x));
}

}  // namespace splat::simd

#pragma GCC diagnostic pop
