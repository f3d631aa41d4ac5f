// The path most material points take in most steps, written once on the
// number type V: double for one point (update_point) and a lane vector for W
// points at once (update_points, the FE element loop). Lane by lane the same
// IEEE operations in the same order (the build has -ffp-contract=off), so a
// point gets the same bits on either path, on any instruction set.
//
// It covers, for a material whose strength law is Johnson-Cook,
//   - an elastic step (trial stress inside the yield surface), and
//   - a plastic step that continues plastic flow: the radial return's first
//     evaluation at the previous step's plastic increment, with B eps^n from
//     the binomial series and the rate factor from the previous step, ending
//     there or with one Taylor-bounded Halley step (johnson_cook_return's own
//     early exits), or else the return's second evaluation, at that Halley
//     step, with the series again (the rate factor by a series of
//     ln(1 + step / dp)), ending there or with one more Taylor-bounded
//     Halley step; adiabatic heating carried by the thermal series;
// both with either EOS and no damage evolution in the step. Everything else
// (the onset of yield, more than two evaluations, damage initiation or
// growth, a heating step the series does not cover, no strength left) is
// reported as not done, and update_point's general path takes the point from
// its unchanged state. Both paths make the same choice for the same point,
// so a run's bits do not depend on which of them met a point first.
#pragma once

#include <variant>

#include "solver/common/simd_lanes.hpp"
#include "solver/material/eos.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update.hpp"

namespace splat {

// The fields of a PointState the fast path reads and writes, on V. The
// deviator is symmetric: s = (xx, yy, zz, xy, yz, xz).
template <class V>
struct PointFields {
  V s[6];
  V p, J, e, eps_p, eps_dot_p, temp, D, sigma_y, sigma_y_static, hardening, strength_scale,
      sigma_y_peak, plastic_work, sigma_y_static_peak;
};

// Whether a 3x3 matrix is exactly symmetric (the fast path's inputs must be).
SPLAT_LANE_INLINE bool is_symmetric(const Mat3& a) {
  return a(0, 1) == a(1, 0) && a(0, 2) == a(2, 0) && a(1, 2) == a(2, 1);
}

// Row and column of component k of the symmetric 6-vectors above.
inline constexpr int sym_row[6] = {0, 1, 2, 0, 1, 0};
inline constexpr int sym_col[6] = {0, 1, 2, 1, 2, 2};

// fn(field of f, the same field of PointState) for every scalar field.
template <class V, class F>
SPLAT_LANE_INLINE void for_each_point_field(PointFields<V>& f, F&& fn) {
  fn(f.p, &PointState::p);
  fn(f.J, &PointState::J);
  fn(f.e, &PointState::e);
  fn(f.eps_p, &PointState::eps_p);
  fn(f.eps_dot_p, &PointState::eps_dot_p);
  fn(f.temp, &PointState::T);
  fn(f.D, &PointState::D);
  fn(f.sigma_y, &PointState::sigma_y);
  fn(f.sigma_y_static, &PointState::sigma_y_static);
  fn(f.hardening, &PointState::hardening);
  fn(f.strength_scale, &PointState::strength_scale);
  fn(f.sigma_y_peak, &PointState::sigma_y_peak);
  fn(f.plastic_work, &PointState::plastic_work);
  fn(f.sigma_y_static_peak, &PointState::sigma_y_static_peak);
}

// Advances the points of `st` whose step the fast path covers and returns
// them (true lanes); `evaluations` is the number of return evaluations of
// each of them (0 elastic, 1 or 2 plastic). In the other lanes st holds no
// meaningful values. de = dt sym(L), symmetric as s; the arguments are
// update_point's (no length: no damage here).
template <class V>
SPLAT_LANE_INLINE LaneMask<V> point_update_fast(const Material& m, const MaterialConstants& mc,
                                                const ModelSwitches& sw, PointFields<V>& st,
                                                const V de[6], const V& J_new, double dt,
                                                V& evaluations) {
  using M = LaneMask<V>;
  // Only Johnson-Cook is accelerated: a point of another law is not done.
  const JohnsonCookParams* law = std::get_if<JohnsonCookParams>(&m.strength);
  if (!law) return M{};
  const JohnsonCookParams& jc = *law;
  const V G_d = (1.0 - st.D) * mc.G;
  const V two_g = 2.0 * G_d, three_g = 3.0 * G_d;

  // Elastic predictor s + 2 G_d dev(de); the stress power of the old stress.
  const V tr = (de[0] + de[1]) + de[2];
  const V third = tr / 3.0;
  V s[6];
  for (int k = 0; k < 3; ++k) s[k] = st.s[k] + two_g * (de[k] - third);
  for (int k = 3; k < 6; ++k) s[k] = st.s[k] + two_g * de[k];
  const V power_old =
      ((st.s[0] - st.p) * de[0] + (st.s[1] - st.p) * de[1] + (st.s[2] - st.p) * de[2]) +
      2.0 * ((st.s[3] * de[3] + st.s[4] * de[4]) + st.s[5] * de[5]);
  const V q_trial_sq = 1.5 * (((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]) +
                              2.0 * ((s[3] * s[3] + s[4] * s[4]) + s[5] * s[5]));
  // Yield test on squares (sigma_y_static >= 0).
  const M plastic = q_trial_sq > st.sigma_y_static * st.sigma_y_static;
  M done = !plastic;
  evaluations = V{};

  const V scale = st.strength_scale;  // (1 - D)(1 - T*^m)
  V dp{}, hard = st.hardening, rate = V{} + 1.0, hard_rate{};
  V end_scale = scale, T_new = st.temp, work_total = st.plastic_work;
  // Damage evolution in a plastic step is not covered: such a point is left
  // to the general path before any work on it.
  const bool damage_on = sw.damage && m.damage.initiation != DamageInitiation::none;
  if constexpr (!is_lane<V>) {
    if (plastic && damage_on) return false;
  }
  if (lane_any(plastic) && !damage_on) {
    // First evaluation of the return at the previous increment (see
    // johnson_cook_return): g(dp) = q_trial - 3 G_d dp - scale hard(dp) rate(dp).
    const V q_trial = lane_sqrt(q_trial_sq);
    const V hi0 = q_trial / three_g;
    const V tol_g = 1e-11 * q_trial;
    const V dp0 = st.eps_dot_p * dt;
    // sigma_y = sigma_y_static R after a plastic step: R at the guess.
    const V rate_guess =
        st.eps_dot_p > 0.0 && st.sigma_y_static > 0.0 ? st.sigma_y / st.sigma_y_static : V{};
    M ok = plastic && scale > 0.0 && dp0 > 0.0 && dp0 < hi0 && st.eps_p > 0.0;
    const V inv_ep = 1.0 / (st.eps_p + dp0);
    M series_ok;
    const V b_pw =
        jc_hardening_series(jc, mc.jc_series, st.hardening - jc.A, dp0 / st.eps_p, series_ok);
    const V hard0 = jc.A + b_pw;
    const V d_hard = jc.n * b_pw * inv_ep;
    const V dd_hard = (jc.n - 1.0) * d_hard * inv_ep;
    const bool rate_on = sw.rate_hardening && jc.C > 0.0;
    const double inv_ref = 1.0 / (jc.eps_dot_0 * dt);  // dp -> eps_dot / eps_dot_0
    const V x = dp0 * inv_ref;
    const M x_above = x > 1.0;
    const M rate_m = rate_on ? x_above : M{};
    ok = ok && series_ok && (!rate_m || rate_guess > 1.0);
    const V inv_dp = rate_m ? 1.0 / dp0 : V{};
    const V rate0 = rate_m ? 1.0 + (rate_guess - 1.0) : V{} + 1.0;
    const V d_rate = rate_m ? jc.C * inv_dp : V{};
    const V dd_rate = rate_m ? -d_rate * inv_dp : V{};
    // First evaluation, at the guess.
    const ReturnEvaluation<V> e0 = jc_return_evaluation(
        jc, q_trial, three_g, scale, tol_g, inv_ref, rate_on, x_above, rate_m, dp0, V{}, hi0, hard0,
        d_hard, dd_hard, inv_ep, rate0, d_rate, dd_rate, inv_dp);
    const M first = e0.at_dp || e0.taylor;
    // The return's second evaluation, at next, where the first did not end
    // it (the increment changed by more than the Taylor bound allows): B
    // eps^n again by the series, now in next / eps_p, and the rate factor
    // from the first's by ln(next / dp0) = ln(1 + step / dp0) by its series.
    // It ends there, or after one more Taylor-bounded Halley step.
    const V next = e0.next;
    M second = ok && !first && next > e0.lo && next < e0.hi && next != dp0 && e0.rate_side;
    V dp2 = next, hard2 = e0.hard_n, rate2 = e0.rate_n, hard_rate2 = e0.hard_rate_n;
    if (lane_any(second)) {
      const V inv_ep1 = 1.0 / (st.eps_p + next);
      M series1_ok{}, log_ok{};
      const V b_pw1 =
          jc_hardening_series(jc, mc.jc_series, st.hardening - jc.A, next / st.eps_p, series1_ok);
      const V hard1 = jc.A + b_pw1;
      const V d_hard1 = jc.n * b_pw1 * inv_ep1;
      const V dd_hard1 = (jc.n - 1.0) * d_hard1 * inv_ep1;
      const V rate1 = rate_m ? rate0 + jc.C * log1p_series(e0.step * inv_dp, log_ok) : V{} + 1.0;
      const V inv_dp1 = rate_m ? 1.0 / next : V{};
      const V d_rate1 = rate_m ? jc.C * inv_dp1 : V{};
      const V dd_rate1 = rate_m ? -d_rate1 * inv_dp1 : V{};
      const ReturnEvaluation<V> e1 = jc_return_evaluation(
          jc, q_trial, three_g, scale, tol_g, inv_ref, rate_on, x_above, rate_m, next, e0.lo, e0.hi,
          hard1, d_hard1, dd_hard1, inv_ep1, rate1, d_rate1, dd_rate1, inv_dp1);
      second = second && series1_ok && (!rate_m || log_ok) && (e1.at_dp || e1.taylor);
      dp2 = e1.at_dp ? next : e1.next;
      hard2 = e1.at_dp ? hard1 : e1.hard_n;
      rate2 = e1.at_dp ? rate1 : e1.rate_n;
      hard_rate2 = e1.at_dp ? e1.hard_rate : e1.hard_rate_n;
    }
    ok = ok && (first || second);
    evaluations = plastic ? (first ? V{} + 1.0 : V{} + 2.0) : V{};
    const M at_guess = e0.at_dp, taylor = e0.taylor;
    dp = plastic ? (at_guess ? dp0 : taylor ? next : dp2) : V{};
    hard = plastic ? (at_guess ? hard0 : taylor ? e0.hard_n : hard2) : hard;
    rate = at_guess ? rate0 : taylor ? e0.rate_n : rate2;
    hard_rate = at_guess ? e0.hard_rate : taylor ? e0.hard_rate_n : hard_rate2;

    // Radial scaling of the trial deviator onto the yield surface.
    const V factor = lane_max(q_trial - three_g * dp, V{}) / q_trial;
    for (int k = 0; k < 6; ++k) s[k] = plastic ? s[k] * factor : s[k];

    // Adiabatic heating: a fraction chi of the plastic work per unit current
    // volume raises the temperature of mass rho0 / J.
    const V w = scale * hard_rate * dp;  // sigma_y dp, J/m^3 of current volume
    work_total = plastic ? st.plastic_work + J_new * w : st.plastic_work;
    const M heated = sw.adiabatic_heating ? plastic && w > 0.0 : M{};
    T_new = heated ? st.temp + mc.heating * (w * J_new) : st.temp;
    // The end state's strength: the thermal series of an undamaged point;
    // (1 - D) with thermal softening off. Damage evolution is not covered.
    if (sw.thermal_softening) {
      M series_applies;
      const V theta = jc_thermal_series(jc, mc.jc_series, scale, st.temp, T_new, series_applies);
      end_scale = heated ? theta : scale;
      ok = ok && (!heated || (series_applies && st.D == 0.0));
    } else {
      end_scale = heated ? (1.0 - st.D) * 1.0 : scale;
    }
    done = done || (plastic && ok);
  }
  for (int k = 0; k < 6; ++k) st.s[k] = s[k];
  st.eps_p = st.eps_p + dp;
  st.eps_dot_p = dp / dt;

  // Pressure from the EOS at J_new with the energy term implicit in p:
  // e_new = e_old + J_mid/2 (sigma_old + sigma_new) : de, sigma = s - p I.
  const V J_mid = 0.5 * (st.J + J_new);
  st.J = J_new;
  const V power_new = ((s[0] * de[0] + s[1] * de[1]) + s[2] * de[2]) +
                      2.0 * ((s[3] * de[3] + s[4] * de[4]) + s[5] * de[5]);
  const V e_star = st.e + 0.5 * J_mid * (power_old + power_new);
  double gamma_e = 0.0;
  const V p_cold = eos_cold_pressure(m.eos, mc.K, mc.rho0, J_new, gamma_e);
  V p = p_cold + gamma_e * e_star;
  if (gamma_e != 0.0) p = p / (1.0 + 0.5 * gamma_e * J_mid * tr);
  p = p < 0.0 ? (1.0 - st.D) * p : p;  // apply_tension_damage
  st.p = p;
  st.e = e_star - 0.5 * J_mid * p * tr;

  st.temp = T_new;
  st.plastic_work = work_total;
  st.hardening = hard;
  st.strength_scale = end_scale;
  st.sigma_y_static = plastic ? end_scale * hard : st.sigma_y_static;
  // Flow stress of this increment; with no plastic rate, no rate hardening.
  st.sigma_y = plastic ? st.sigma_y_static * rate : st.sigma_y_static;
  st.sigma_y_peak = lane_max(st.sigma_y_peak, st.sigma_y);
  st.sigma_y_static_peak = lane_max(st.sigma_y_static_peak, st.sigma_y_static);
  return done;
}

}  // namespace splat
