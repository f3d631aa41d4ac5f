// The path most material points take in most steps, written once on the
// number type V: double for one point (update_point) and a lane vector for W
// points at once (update_points, the FE element loop). Lane by lane the same
// IEEE operations in the same order (the build has -ffp-contract=off), so a
// point gets the same bits on either path, on any instruction set.
//
// It covers
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
  const JohnsonCookParams& jc = m.strength;
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
    const V hard_rate0 = hard0 * rate0;
    const V g = q_trial - three_g * dp0 - scale * hard_rate0;
    const V lo = g > 0.0 ? dp0 : V{};
    const V hi = g > 0.0 ? hi0 : dp0;
    const M at_guess = lane_abs(g) <= tol_g || hi - lo <= 1e-14 * hi;
    // One Halley step that lands where the Taylor expansions of the
    // hardening and rate terms are exact to 1e-14 ends the return.
    const V slope = -three_g - scale * (d_hard * rate0 + hard0 * d_rate);
    const V curv = -scale * (dd_hard * rate0 + 2.0 * d_hard * d_rate + hard0 * dd_rate);
    const V next = jc_return_step(dp0, g, slope, curv);
    const V step = next - dp0;
    const V rel_h = lane_abs(step) * inv_ep;
    const M rate_side = rate_on ? x_above == (next * inv_ref > 1.0) : !M{};
    const V rel_r = rate_m ? lane_abs(step) * inv_dp : V{};
    const V trunc = jc_taylor_truncation(jc, rel_h, rel_r);
    V hard_n, rate_n;
    jc_taylor_terms(jc, step, hard0, d_hard, dd_hard, inv_ep, rate0, d_rate, dd_rate, inv_dp,
                    hard_n, rate_n);
    const V hard_rate_n = hard_n * rate_n;
    const V g_n = q_trial - three_g * next - scale * hard_rate_n;
    const M taylor = next > lo && next < hi && next != dp0 && rate_side && trunc <= 1e-14 &&
                     lane_abs(g_n) + scale * hard_rate_n * trunc <= tol_g;
    const M first = at_guess || taylor;
    // The return's second evaluation, at next, where the first did not end
    // it (the increment changed by more than the Taylor bound allows): B
    // eps^n again by the series, now in next / eps_p, and the rate factor
    // from the first's by ln(next / dp0) = ln(1 + step / dp0) by its series.
    // It ends there, or after one more Taylor-bounded Halley step.
    M second = ok && !first && next > lo && next < hi && next != dp0 && rate_side;
    V dp2 = next, hard2 = hard_n, rate2 = rate_n, hard_rate2 = hard_rate_n;
    if (lane_any(second)) {
      const V inv_ep1 = 1.0 / (st.eps_p + next);
      M series1_ok, log_ok;
      const V b_pw1 =
          jc_hardening_series(jc, mc.jc_series, st.hardening - jc.A, next / st.eps_p, series1_ok);
      const V hard1 = jc.A + b_pw1;
      const V d_hard1 = jc.n * b_pw1 * inv_ep1;
      const V dd_hard1 = (jc.n - 1.0) * d_hard1 * inv_ep1;
      const V rate1 = rate_m ? rate0 + jc.C * log1p_series(step * inv_dp, log_ok) : V{} + 1.0;
      const V inv_dp1 = rate_m ? 1.0 / next : V{};
      const V d_rate1 = rate_m ? jc.C * inv_dp1 : V{};
      const V dd_rate1 = rate_m ? -d_rate1 * inv_dp1 : V{};
      const V hard_rate1 = hard1 * rate1;
      const V g1 = q_trial - three_g * next - scale * hard_rate1;
      const V lo1 = g1 > 0.0 ? next : lo;
      const V hi1 = g1 > 0.0 ? hi : next;
      const M at_next = lane_abs(g1) <= tol_g || hi1 - lo1 <= 1e-14 * hi1;
      const V slope1 = -three_g - scale * (d_hard1 * rate1 + hard1 * d_rate1);
      const V curv1 = -scale * (dd_hard1 * rate1 + 2.0 * d_hard1 * d_rate1 + hard1 * dd_rate1);
      const V next2 = jc_return_step(next, g1, slope1, curv1);
      const V step2 = next2 - next;
      const V rel_h2 = lane_abs(step2) * inv_ep1;
      const M rate_side2 = rate_on ? x_above == (next2 * inv_ref > 1.0) : !M{};
      const V rel_r2 = rate_m ? lane_abs(step2) * inv_dp1 : V{};
      const V trunc2 = jc_taylor_truncation(jc, rel_h2, rel_r2);
      V hard_n2, rate_n2;
      jc_taylor_terms(jc, step2, hard1, d_hard1, dd_hard1, inv_ep1, rate1, d_rate1, dd_rate1,
                      inv_dp1, hard_n2, rate_n2);
      const V hard_rate_n2 = hard_n2 * rate_n2;
      const V g_n2 = q_trial - three_g * next2 - scale * hard_rate_n2;
      const M taylor2 = next2 > lo1 && next2 < hi1 && next2 != next && rate_side2 &&
                        trunc2 <= 1e-14 && lane_abs(g_n2) + scale * hard_rate_n2 * trunc2 <= tol_g;
      second = second && series1_ok && (!rate_m || log_ok) && (at_next || taylor2);
      dp2 = at_next ? next : next2;
      hard2 = at_next ? hard1 : hard_n2;
      rate2 = at_next ? rate1 : rate_n2;
      hard_rate2 = at_next ? hard_rate1 : hard_rate_n2;
    }
    ok = ok && (first || second);
    evaluations = plastic ? (first ? V{} + 1.0 : V{} + 2.0) : V{};
    dp = plastic ? (at_guess ? dp0 : taylor ? next : dp2) : V{};
    hard = plastic ? (at_guess ? hard0 : taylor ? hard_n : hard2) : hard;
    rate = at_guess ? rate0 : taylor ? rate_n : rate2;
    hard_rate = at_guess ? hard_rate0 : taylor ? hard_rate_n : hard_rate2;

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
