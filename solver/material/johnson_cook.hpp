// Johnson-Cook flow stress (thesis eq. 1.26) and its radial return.
//
//   sigma_y = (A + B eps_p^n) (1 + C ln max(eps_dot_p / eps_dot_0, 1)) (1 - T*^m),
//   T* = (T - T_ref) / (T_melt - T_ref) clamped to [0, 1],
// so there is no strength gain below the reference rate, no extra strength
// below the reference temperature and no strength at or above melt. Each of
// the rate and thermal terms can be switched off (factor 1).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/common/simd_lanes.hpp"
#include "solver/material/model_switches.hpp"
#include "solver/material/strength_law.hpp"

namespace splat {

// Johnson & Cook (1983), thesis eq. 1.26 (above).
struct JohnsonCookParams {
  static constexpr const char* model = "johnson-cook";
  double A = 0.0;          // initial yield stress, Pa
  double B = 0.0;          // hardening modulus, Pa
  double n = 1.0;          // hardening exponent, -
  double C = 0.0;          // strain-rate sensitivity, -
  double eps_dot_0 = 1.0;  // reference plastic strain rate, 1/s
  double m = 1.0;          // thermal softening exponent, -
  double T_ref = 300.0;    // reference (room) temperature, K
  double T_melt = 1000.0;  // melting temperature, K

  static constexpr std::array<LawField<JohnsonCookParams>, 8> fields() {
    using P = JohnsonCookParams;
    return {{{"A", &P::A, Quantity::yield_stress},
             {"B", &P::B, Quantity::hardening_stress},
             {"n", &P::n, Quantity::dimensionless},
             {"C", &P::C, Quantity::dimensionless},
             {"eps_dot_0", &P::eps_dot_0, Quantity::rate},
             {"m", &P::m, Quantity::dimensionless},
             {"T_ref", &P::T_ref, Quantity::room_temperature},
             {"T_melt", &P::T_melt, Quantity::melting_temperature}}};
  }
};

inline StrengthReferences strength_references(const JohnsonCookParams& jc) {
  return {jc.eps_dot_0, jc.T_ref, jc.T_melt};
}

inline double jc_thermal_factor(const JohnsonCookParams& jc, bool enabled, double T) {
  if (!enabled) return 1.0;
  const double t_star = (T - jc.T_ref) / (jc.T_melt - jc.T_ref);
  if (t_star <= 0.0) return 1.0;
  if (t_star >= 1.0) return 0.0;
  return 1.0 - std::exp(jc.m * std::log(t_star));  // t_star^m: exp and log cost less than pow
}

// Binomial coefficients of the series shortcuts below, derived once per
// material (MaterialConstants::jc_series).
struct JcSeries {
  double hardening[14] = {};  // binom(n, k), k = 0..13
  double thermal[8] = {};     // binom(m, k), k = 0..7
};
JcSeries jc_series(const JohnsonCookParams& jc);

// jc_thermal_factor at T_new > T_old from theta_old, its value at T_old.
// For a small heating step, T* = (T - T_ref) / (T_melt - T_ref) in (0, 1),
// 1 - theta = T*^m is carried by the binomial series of degree 6,
//   T*_new^m = T*_old^m (1 + w)^m,  w = (T_new - T_old) / (T_old - T_ref),
// with no exp or log; used only for w <= 1/16 (so that (1 + w)^m, m <= 7,
// amplifies the rounding of T*_old^m = 1 - theta_old at most 1.6-fold) and
// where the remainder |binom(m, 7)| w^7 times T*_old^m is below 1e-17, else
// jc_thermal_factor evaluates it. Each step adds a rounding error of about
// 1e-16 to theta.
double jc_thermal_factor_after_heating(const JohnsonCookParams& jc, const JcSeries& series,
                                       double theta_old, double T_old, double T_new);

// The series of jc_thermal_factor_after_heating on the number type V (double
// or lanes): its value, and in `ok` where it applies (elsewhere the value is
// meaningless and jc_thermal_factor is needed).
template <class V>
SPLAT_LANE_INLINE V jc_thermal_series(const JohnsonCookParams& jc, const JcSeries& series,
                                      const V& theta_old, const V& T_old, const V& T_new,
                                      LaneMask<V>& ok) {
  const double m = jc.m;
  const double span = jc.T_melt - jc.T_ref;
  const V above = T_old - jc.T_ref;
  // w <= 1/16: (1 + w)^m amplifies the rounding of p_old at most 1.6-fold.
  const V w = (T_new - T_old) / above;
  const V p_old = 1.0 - theta_old;  // T*_old^m
  const double* c = series.thermal;
  const V w2 = w * w, w4 = w2 * w2;
  ok = above > 0.0 && T_new >= T_old && T_new - jc.T_ref < span && w <= 0.0625 &&
       p_old * std::abs(c[7]) * (w4 * w2 * w) <= 1e-17;
  if (!(m <= 7.0 && span > 0.0)) ok = LaneMask<V>{};
  const V q1 = c[1] + c[2] * w, q3 = c[3] + c[4] * w, q5 = c[5] + c[6] * w;
  const V sum = w * ((q1 + q3 * w2) + q5 * w4);  // (1 + w)^m - 1
  return 1.0 - (p_old + p_old * sum);
}

// B (eps_p + dp)^n from P0 = B eps_p^n (eps_p > 0) and u = dp / eps_p >= 0
// by the binomial series of degree 12, (1 + u)^n = sum binom(n, k) u^k: no
// exp or log. Its remainder is binom(n, 13) u^13 (1 + xi)^(n - 13) <=
// |binom(n, 13)| u^13 for n <= 13; `ok` marks where that, times P0, is below
// 1e-17 of A + P0 (the rounding of exp(n log ep) is ~1e-16): for n = 0.31
// (copper) up to u = 0.07, a plastic increment of 7 % of the plastic strain
// so far. Elsewhere the caller evaluates exp and log.
template <class V>
SPLAT_LANE_INLINE V jc_hardening_series(const JohnsonCookParams& jc, const JcSeries& series,
                                        const V& P0, const V& u, LaneMask<V>& ok) {
  const double* c = series.hardening;
  const V u2 = u * u, u4 = u2 * u2, u8 = u4 * u4;
  ok = u >= 0.0 && !(P0 * std::abs(c[13]) * (u8 * u4 * u) > 1e-17 * (jc.A + P0));
  if (!(jc.n <= 13.0)) ok = LaneMask<V>{};
  // Estrin's scheme: sum_{k=1..12} c_k u^k with a short dependency chain.
  const V q1 = c[1] + c[2] * u, q3 = c[3] + c[4] * u, q5 = c[5] + c[6] * u, q7 = c[7] + c[8] * u,
          q9 = c[9] + c[10] * u, q11 = c[11] + c[12] * u;
  const V sum =
      u * (((q1 + q3 * u2) + (q5 + q7 * u2) * u4) + (q9 + q11 * u2) * u8);  // (1 + u)^n - 1
  return P0 + P0 * sum;
}

inline double jc_rate_factor(const JohnsonCookParams& jc, bool enabled, double eps_dot_p) {
  if (!enabled || eps_dot_p <= jc.eps_dot_0) return 1.0;
  return 1.0 + jc.C * std::log(eps_dot_p / jc.eps_dot_0);
}

inline double jc_hardening(const JohnsonCookParams& jc, double eps_p) {
  return eps_p > 0.0 ? jc.A + jc.B * std::pow(eps_p, jc.n) : jc.A;
}

// Flow stress and its partial derivatives at (eps_p, eps_dot_p, T).
FlowStress johnson_cook_flow_stress(const JohnsonCookParams& jc, const ModelSwitches& sw,
                                    double eps_p, double eps_dot_p, double T);

// The same under the name every law gives its flow stress (no pressure
// dependence).
inline FlowStress flow_stress(const JohnsonCookParams& jc, const ModelSwitches& sw, double eps_p,
                              double eps_dot_p, double T, const PressureState& /*state*/) {
  return johnson_cook_flow_stress(jc, sw, eps_p, eps_dot_p, T);
}

// Pieces of the radial return below shared with its lanes
// (point_update_fast.hpp), on the number type V (double or lanes).
//
// Halley's step dp - 2 g g' / (2 g'^2 - g g'') (cubic convergence), Newton's
// dp - g / g' where the curvature term g g'' is not small.
template <class V>
SPLAT_LANE_INLINE V jc_return_step(const V& dp, const V& g, const V& slope, const V& curv) {
  const V gc = g * curv, s2 = 2.0 * slope * slope;
  // One division for both (lanes would compute both quotients).
  const auto halley = lane_abs(gc) < 0.5 * s2;
  return dp - (halley ? 2.0 * g * slope : g) / (halley ? s2 - gc : slope);
}

// Bound on the truncation error, relative to the flow stress, of the
// third-order Taylor expansions of A + B eps^n and 1 + C ln(x) over a step of
// relative size rel_h (to eps_p + dp) and rel_r (to dp): (n + 3)^4 rel_h^4 +
// |C| rel_r^4 (see johnson_cook_return).
template <class V>
SPLAT_LANE_INLINE V jc_taylor_truncation(const JohnsonCookParams& jc, const V& rel_h,
                                         const V& rel_r) {
  const double n3 = (jc.n + 3.0) * (jc.n + 3.0);
  const V h2 = rel_h * rel_h, r2 = rel_r * rel_r;
  return n3 * n3 * h2 * h2 + std::abs(jc.C) * r2 * r2;
}

// The hardening and rate terms a step on, by those expansions, from their
// values and first two derivatives at dp (third derivatives (n - 2) dd_hard /
// ep and -2 dd_rate / dp; inv_ep = 1 / ep, inv_dp = 1 / dp).
template <class V>
SPLAT_LANE_INLINE void jc_taylor_terms(const JohnsonCookParams& jc, const V& step, const V& hard,
                                       const V& d_hard, const V& dd_hard, const V& inv_ep,
                                       const V& rate, const V& d_rate, const V& dd_rate,
                                       const V& inv_dp, V& hard_n, V& rate_n) {
  const V d3_hard = (jc.n - 2.0) * dd_hard * inv_ep;
  const V d3_rate = -2.0 * dd_rate * inv_dp;
  hard_n = hard + step * (d_hard + step * (0.5 * dd_hard + step * (d3_hard * (1.0 / 6.0))));
  rate_n = rate + step * (d_rate + step * (0.5 * dd_rate + step * (d3_rate * (1.0 / 6.0))));
}

// One evaluation of the radial return at dp (an iteration of
// johnson_cook_return, and of the fast path's lanes), given the hardening and
// rate terms there and their first two derivatives: the residual's bracket
// [lo, hi] after it, whether the return ends at dp, and else its Halley step
// and whether the Taylor-bounded end there ends it (with the expanded terms).
// x_above: dp / (eps_dot_0 dt) > 1; rate_m: the rate term is on at dp.
template <class V>
struct ReturnEvaluation {
  V hard_rate, lo, hi, next, step, hard_n, rate_n, hard_rate_n;
  LaneMask<V> at_dp, rate_side, taylor;
};

template <class V>
SPLAT_LANE_INLINE ReturnEvaluation<V> jc_return_evaluation(
    const JohnsonCookParams& jc, const V& q_trial, const V& three_g, const V& scale, const V& tol_g,
    double inv_ref, bool rate_on, const LaneMask<V>& x_above, const LaneMask<V>& rate_m,
    const V& dp, const V& lo, const V& hi, const V& hard, const V& d_hard, const V& dd_hard,
    const V& inv_ep, const V& rate, const V& d_rate, const V& dd_rate, const V& inv_dp) {
  ReturnEvaluation<V> r;
  r.hard_rate = hard * rate;
  const V g = q_trial - three_g * dp - scale * r.hard_rate;
  r.lo = g > 0.0 ? dp : lo;
  r.hi = g > 0.0 ? hi : dp;
  r.at_dp = lane_abs(g) <= tol_g || r.hi - r.lo <= 1e-14 * r.hi;
  // One Halley step that lands where the Taylor expansions of the
  // hardening and rate terms are exact to 1e-14 ends the return.
  const V slope = -three_g - scale * (d_hard * rate + hard * d_rate);
  const V curv = -scale * (dd_hard * rate + 2.0 * d_hard * d_rate + hard * dd_rate);
  r.next = jc_return_step(dp, g, slope, curv);
  r.step = r.next - dp;
  const V rel_h = lane_abs(r.step) * inv_ep;
  r.rate_side = rate_on ? x_above == (r.next * inv_ref > 1.0) : !LaneMask<V>{};
  const V rel_r = rate_m ? lane_abs(r.step) * inv_dp : V{};
  const V trunc = jc_taylor_truncation(jc, rel_h, rel_r);
  jc_taylor_terms(jc, r.step, hard, d_hard, dd_hard, inv_ep, rate, d_rate, dd_rate, inv_dp,
                  r.hard_n, r.rate_n);
  r.hard_rate_n = r.hard_n * r.rate_n;
  const V g_n = q_trial - three_g * r.next - scale * r.hard_rate_n;
  r.taylor = r.next > r.lo && r.next < r.hi && r.next != dp && r.rate_side && trunc <= 1e-14 &&
             lane_abs(g_n) + scale * r.hard_rate_n * trunc <= tol_g;
  return r;
}

struct ReturnMapResult {
  double delta_eps_p = 0.0;  // plastic strain increment, -
  double hard_rate = 0.0;    // (A + B eps_p^n)(1 + C ln eps_dot*) at the solution, Pa
  double hard = 0.0;         // A + B (eps_p + dp)^n at the solution, Pa
  double rate = 1.0;         // 1 + C ln max(eps_dot*, 1) at the solution, -
  int iterations = 0;        // Newton or bisection iterations used
  bool converged = true;
};

// Radial return for von Mises plasticity with Johnson-Cook hardening: finds
// dp >= 0 with
//   g(dp) = q_trial - 3 G_d dp - scale (A + B (eps_p + dp)^n) R(dp / dt) = 0,
// where scale = (1 - D) (1 - T*^m) is fixed over the step (temperature and
// damage are those at the start of the step: staggered update), G_d is the
// damaged shear modulus, and hard0 = A + B eps_p^n the hardening term at the
// start (already known to the caller from its yield check); dp_guess > 0
// (typically the previous step's plastic rate times dt) seeds Newton, else the
// linearised-hardening estimate does. g(0) > 0 (the
// caller checked yielding), g(q_trial / 3 G_d) <= 0, and g is strictly
// decreasing, so the root is unique and bracketed. Halley steps (Newton's
// where g's curvature term is not small) from the guess are kept inside the
// shrinking bracket; a step that would leave it bisects instead. A last step
// small enough for Taylor expansions of the hardening and rate terms to be
// exact to 1e-14 ends the iteration without one more evaluation (hard, rate
// and hard_rate are then those expansions). This converges for every state: near
// melt (scale -> 0), at rates 1e-3 to 1e8 /s, and where d sigma / d eps_p is
// unbounded (n < 1 at eps_p = 0).
// Continued plastic flow (series given): rate_guess is R at dp_guess (the
// previous step's rate factor; 0 if not known). The first evaluation, at
// dp_guess with eps_p > 0, takes B (eps_p + dp_guess)^n from hard0 by the
// binomial series of degree 12 in dp_guess / eps_p, where its remainder is
// below 1e-17 of the hardening term, and the rate factor from rate_guess
// (> 1), instead of exp and log.
ReturnMapResult johnson_cook_return(const JohnsonCookParams& jc, bool rate_hardening,
                                    double q_trial, double G_d, double eps_p, double dt,
                                    double scale, double hard0, double dp_guess = 0.0,
                                    double rate_guess = 0.0, const JcSeries* series = nullptr);

}  // namespace splat
