#include "solver/material/point_update_batch.hpp"

#include <algorithm>
#include <utility>

#include "solver/common/simd_math.hpp"
#include "solver/material/damage.hpp"
#include "solver/material/eos.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update_kernel.hpp"

// Vector values never cross a call boundary here (everything below is
// inlined into the clones of update_points).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace splat {

namespace {

using V = simd::v8d;  // 8 points per block (4 and 16 measured slower; see the benchmark)
using M = simd::mask_t<V>;
constexpr int W = simd::lanes<V>;

// Vector iterations of the return before the lanes still running are handed
// to update_point (its own limit is 200; the usual count is 1 to 3).
constexpr int max_vector_iterations = 12;

[[gnu::always_inline]] inline V bc(double c) {
  return simd::broadcast<V>(c);
}
[[gnu::always_inline]] inline M mtrue() {
  return simd::broadcast_int<V>(-1);
}
[[gnu::always_inline]] inline M mfalse() {
  return simd::broadcast_int<V>(0);
}

// The vector {field(0), ..., field(W - 1)}, built in registers.
template <class F, std::size_t... L>
[[gnu::always_inline]] inline V make_lanes(F field, std::index_sequence<L...>) {
  return V{field(L)...};
}

// The result of johnson_cook_return in lanes; `redo` marks lanes that left
// the common path (no strength, not converged within max_vector_iterations).
struct ReturnLanes {
  V dp, hard, rate, hard_rate, iterations;
  M redo;
};

// johnson_cook_return (johnson_cook.cpp) for the lanes in `plastic`, the same
// operations in the same order; a lane stops where the scalar loop breaks.
[[gnu::always_inline]] inline ReturnLanes return_lanes(const JohnsonCookParams& jc,
                                                       bool rate_hardening, M plastic, V q_trial,
                                                       V G_d, V eps_p, double dt, V scale, V hard0,
                                                       V dp_guess) {
  using simd::abs;
  using simd::mask_and;
  using simd::mask_not;
  using simd::mask_or;
  using simd::select;
  ReturnLanes r;
  const V three_g = 3.0 * G_d;
  const bool rate_on = rate_hardening && jc.C > 0.0;
  const M rate_on_m = rate_on ? mtrue() : mfalse();
  const double inv_ref = 1.0 / (jc.eps_dot_0 * dt);
  const M strength = scale > 0.0;
  r.redo = mask_and(plastic, mask_not(strength));
  M act = mask_and(plastic, strength);
  V lo = bc(0.0);
  V hi = q_trial / three_g;
  const V tol_g = 1e-11 * q_trial;
  const double h0_zero = jc.n == 1.0 ? jc.B : 0.0;
  const V h0 = select<V>(eps_p > 0.0, jc.n * (hard0 - jc.A) / eps_p, bc(h0_zero));
  const V linear = simd::min<V>(hi, (q_trial - scale * hard0) / (three_g + scale * h0));
  V dp = select<V>(mask_and(dp_guess > 0.0, dp_guess < hi), dp_guess, linear);
  r.dp = dp;
  r.hard = r.rate = r.hard_rate = r.iterations = bc(0.0);
  const double n3 = (jc.n + 3.0) * (jc.n + 3.0);
  const double abs_C = std::abs(jc.C);
  auto finish = [&](M done, V dp_d, V hard, V rate, V hard_rate, double it) {
    r.dp = select<V>(done, dp_d, r.dp);
    r.hard = select<V>(done, hard, r.hard);
    r.rate = select<V>(done, rate, r.rate);
    r.hard_rate = select<V>(done, hard_rate, r.hard_rate);
    r.iterations = select<V>(done, bc(it), r.iterations);
    act = mask_and(act, mask_not(done));
  };
  for (int it = 1; it <= max_vector_iterations && simd::any(act); ++it) {
    const V ep = eps_p + dp;
    const M ep_pos = ep > 0.0;
    const V pw = simd::exp(jc.n * simd::log(ep));
    const V inv_ep = 1.0 / ep;
    const V d_hard_raw = jc.B * jc.n * pw * inv_ep;
    const V hard = select<V>(ep_pos, jc.A + jc.B * pw, bc(jc.A));
    const V d_hard = select<V>(ep_pos, d_hard_raw, bc(0.0));
    const V dd_hard = select<V>(ep_pos, (jc.n - 1.0) * d_hard_raw * inv_ep, bc(0.0));
    const V x = dp * inv_ref;
    const M x_above = x > 1.0;
    const M rate_m = mask_and(rate_on_m, x_above);
    const V inv_dp = 1.0 / dp;
    const V d_rate_raw = jc.C * inv_dp;
    const V rate = select<V>(rate_m, 1.0 + jc.C * simd::log(x), bc(1.0));
    const V d_rate = select<V>(rate_m, d_rate_raw, bc(0.0));
    const V dd_rate = select<V>(rate_m, -d_rate_raw * inv_dp, bc(0.0));
    const V hard_rate = hard * rate;
    const V g = q_trial - three_g * dp - scale * hard_rate;
    finish(mask_and(act, abs(g) <= tol_g), dp, hard, rate, hard_rate, it);
    const M g_pos = g > 0.0;
    lo = select<V>(mask_and(act, g_pos), dp, lo);
    hi = select<V>(mask_and(act, mask_not(g_pos)), dp, hi);
    finish(mask_and(act, hi - lo <= 1e-14 * hi), dp, hard, rate, hard_rate, it);
    if (!simd::any(act)) break;
    const V slope = -three_g - scale * (d_hard * rate + hard * d_rate);
    const V curv = -scale * (dd_hard * rate + 2.0 * d_hard * d_rate + hard * dd_rate);
    const V gc = g * curv, s2 = 2.0 * slope * slope;
    const V next = select<V>(abs(gc) < 0.5 * s2, dp - 2.0 * g * slope / (s2 - gc), dp - g / slope);
    const M bisect = mask_or(mask_not(mask_and(next > lo, next < hi)), next == dp);
    // Taylor-bounded last step (see johnson_cook_return).
    const V step = next - dp;
    const V rel_h = abs(step) / ep;
    const M rate_side = rate_on ? ~(x_above ^ (next * inv_ref > 1.0)) : mtrue();
    const V rel_r = select<V>(rate_m, abs(step) / dp, bc(0.0));
    const V h2 = rel_h * rel_h, r2 = rel_r * rel_r;
    const V trunc = n3 * n3 * h2 * h2 + abs_C * r2 * r2;
    const M taylor = mask_and(mask_and(act, mask_not(bisect)), mask_and(rate_side, trunc <= 1e-14));
    if (simd::any(taylor)) {
      const V d3_hard = select<V>(ep_pos, (jc.n - 2.0) * dd_hard / ep, bc(0.0));
      const V d3_rate = select<V>(rel_r > 0.0, -2.0 * dd_rate / dp, bc(0.0));
      const V hard_n = hard + step * (d_hard + step * (0.5 * dd_hard + step * (d3_hard / 6.0)));
      const V rate_n = rate + step * (d_rate + step * (0.5 * dd_rate + step * (d3_rate / 6.0)));
      const V hard_rate_n = hard_n * rate_n;
      const V g_n = q_trial - three_g * next - scale * hard_rate_n;
      finish(mask_and(taylor, abs(g_n) + scale * hard_rate_n * trunc <= tol_g), next, hard_n,
             rate_n, hard_rate_n, it);
    }
    dp = select<V>(act, select<V>(bisect, 0.5 * (lo + hi), next), dp);
  }
  r.redo = mask_or(r.redo, act);
  return r;
}

// One block of up to W points: k0 .. k0 + count - 1.
[[gnu::always_inline]] inline void update_block(const Material& m, const MaterialConstants& mc,
                                                const ModelSwitches& sw, PointState* states,
                                                const int* index, std::size_t k0, int count,
                                                const Mat3* d_eps, const double* J_new, double dt,
                                                const double* length, PointUpdateResult* out) {
  using simd::select;
  // Gather; padding lanes repeat the last point and are not written back.
  // Each vector is built from its lanes in registers (lane stores into a
  // vector in memory followed by a vector load stall store forwarding).
  const PointState* st_l[W];
  const double* d_l[W];
  for (int l = 0; l < W; ++l) {
    const std::size_t k = k0 + static_cast<std::size_t>(std::min(l, count - 1));
    st_l[l] = &states[index[k]];
    d_l[l] = d_eps[k].data();
  }
#define SPLAT_LANES(expr) \
  make_lanes([&](std::size_t l) { return expr; }, std::make_index_sequence<W>())
  V s_old[9], de[9];
  for (int i = 0; i < 9; ++i) {
    s_old[i] = SPLAT_LANES(st_l[l]->s.data()[i]);
    de[i] = SPLAT_LANES(d_l[l][i]);
  }
  const V p_old = SPLAT_LANES(st_l[l]->p);
  const V J_old = SPLAT_LANES(st_l[l]->J);
  const V J_n = SPLAT_LANES(J_new[k0 + std::min(l, static_cast<std::size_t>(count - 1))]);
  const V e_old = SPLAT_LANES(st_l[l]->e);
  const V eps_p = SPLAT_LANES(st_l[l]->eps_p);
  const V eps_dot_p = SPLAT_LANES(st_l[l]->eps_dot_p);
  const V T = SPLAT_LANES(st_l[l]->T);
  const V D = SPLAT_LANES(st_l[l]->D);
  const V sy_static = SPLAT_LANES(st_l[l]->sigma_y_static);
  const V hardening = SPLAT_LANES(st_l[l]->hardening);
  const V scale = SPLAT_LANES(st_l[l]->strength_scale);
  const V sy_peak = SPLAT_LANES(st_l[l]->sigma_y_peak);
  const V sy_static_peak = SPLAT_LANES(st_l[l]->sigma_y_static_peak);
  const V work = SPLAT_LANES(st_l[l]->plastic_work);
  const V omega = SPLAT_LANES(st_l[l]->omega);
  const V eps_p_init = SPLAT_LANES(st_l[l]->eps_p_init);

  // Elastic predictor and yield check (update_point).
  const V G_d = (1.0 - D) * mc.G;
  V s[9];
  point_kernel::elastic_predictor(s_old, de, 2.0 * G_d, s);
  const V q_trial = point_kernel::von_mises9(s);
  const V power_old = point_kernel::stress_power9(s_old, p_old, de);
  const M plastic = q_trial > sy_static;
  ReturnLanes rm{bc(0.0), bc(0.0), bc(1.0), bc(0.0), bc(0.0), mfalse()};
  V dp = bc(0.0);
  if (simd::any(plastic)) {
    rm = return_lanes(m.strength, sw.rate_hardening, plastic, q_trial, G_d, eps_p, dt, scale,
                      hardening, eps_dot_p * dt);
    dp = select<V>(plastic, rm.dp, bc(0.0));
    const V factor = simd::max<V>(q_trial - 3.0 * G_d * dp, bc(0.0)) / q_trial;
    for (V& si : s) si = select<V>(plastic, si * factor, si);
  }
  const V eps_p_new = eps_p + dp;
  const V eps_dot_p_new = dp / dt;

  // EOS and energy.
  const V J_mid = 0.5 * (J_old + J_n);
  const V tr = (de[0] + de[4]) + de[8];
  const V power_new = point_kernel::sum_products9(s, de);
  const V e_star = e_old + 0.5 * J_mid * (power_old + power_new);
  const EosSplitT<V> eos = eos_split_t<V>(m.eos, mc.K, mc.rho0, J_n);
  V p = (eos.p_cold + eos.gamma_e * e_star) / (1.0 + 0.5 * eos.gamma_e * J_mid * tr);
  p = apply_tension_damage_t<V>(p, D);
  const V e_new = e_star - 0.5 * J_mid * p * tr;

  // Heating.
  const M flowed = dp > 0.0;
  const V hardening_new = select<V>(flowed, rm.hard, hardening);
  const V sy_increment = scale * rm.hard_rate;
  const V w = sy_increment * dp;
  const V work_new = select<V>(flowed, work + J_n * w, work);
  const M heated =
      simd::mask_and(sw.adiabatic_heating ? mtrue() : mfalse(), simd::mask_and(flowed, w > 0.0));
  const V T_new = select<V>(heated, T + mc.chi * w * J_n / (mc.rho0 * mc.c_p), T);

  // Damage (update_damage) in lanes: Johnson-Cook initiation for the points
  // not yet initiated that stay so, and the evolution of points initiated in
  // an earlier step. Points whose damage starts in this step, and shear
  // initiation (principal stresses), finish in finish_plastic_step.
  const bool damage_on = sw.damage && m.damage.initiation != DamageInitiation::none;
  M damage_scalar = damage_on ? flowed : mfalse();
  V omega_new = omega;
  V D_new = D;
  if (damage_on && simd::any(flowed)) {
    const DamageParams& dm = m.damage;
    const M fresh = simd::mask_and(flowed, eps_p_init < 0.0);
    const M initiated = simd::mask_and(flowed, simd::mask_not(eps_p_init < 0.0));
    M in_lanes = initiated;
    if (dm.initiation == DamageInitiation::johnson_cook) {
      const V q_new = point_kernel::von_mises9(s);
      const V eta = select<V>(q_new > 0.0, -p / q_new, bc(0.0));
      const V eps_f = jc_failure_strain_t<V>(dm.jc, m.strength, sw.rate_hardening,
                                             sw.thermal_softening, eta, dp / dt, T_new);
      const V omega_step = omega + dp / eps_f;
      const M stays = simd::mask_and(fresh, omega_step < 1.0);
      omega_new = select<V>(stays, omega_step, omega);
      in_lanes = simd::mask_or(in_lanes, stays);
    }
    V D_evolved = D;
    switch (dm.evolution) {
      case DamageEvolution::instant:
        D_evolved = bc(dm.D_max);
        break;
      case DamageEvolution::plastic_strain: {
        const V span = dm.eps_p_max - eps_p_init;
        D_evolved = select<V>(span > 0.0, D + dp / span, bc(dm.D_max));
        break;
      }
      case DamageEvolution::fracture_energy: {
        const V length_l =
            SPLAT_LANES(length[k0 + std::min(l, static_cast<std::size_t>(count - 1))]);
        D_evolved = D + dm.D_max * sy_increment * dp * length_l / dm.G_f;
        break;
      }
    }
    // std::min(std::max(D, D_old), D_max)
    D_new = select<V>(initiated, simd::min<V>(simd::max<V>(D_evolved, D), bc(dm.D_max)), D);
    damage_scalar = simd::mask_and(flowed, simd::mask_not(in_lanes));
  }

  // The strength of the end state: temperature or damage moved.
  const M moved = simd::mask_or(heated, D_new != D);
  V end_scale = scale;
  if (simd::any(moved)) {
    end_scale = select<V>(
        moved, (1.0 - D_new) * jc_thermal_factor_t<V>(m.strength, sw.thermal_softening, T_new),
        scale);
  }
  const V sy_static_new = select<V>(flowed, end_scale * hardening_new, sy_static);
  const V sy_new = select<V>(flowed, sy_static_new * rm.rate, sy_static);
  const V sy_peak_new = simd::max<V>(sy_peak, sy_new);
  const V sy_static_peak_new = simd::max<V>(sy_static_peak, sy_static_new);

#undef SPLAT_LANES

  // Scatter.
  for (int l = 0; l < count; ++l) {
    const std::size_t k = k0 + static_cast<std::size_t>(l);
    PointState& st = states[index[k]];
    if (rm.redo[l]) {  // a rare path: update_point from the untouched state
      out[k] = update_point(m, mc, sw, st, d_eps[k], J_new[k], dt, length[k]);
      continue;
    }
    double* so = st.s.data();
    for (int i = 0; i < 9; ++i) so[i] = s[i][l];
    st.p = p[l];
    st.J = J_n[l];
    st.e = e_new[l];
    st.eps_p = eps_p_new[l];
    st.eps_dot_p = eps_dot_p_new[l];
    st.T = T_new[l];
    st.hardening = hardening_new[l];
    st.plastic_work = work_new[l];
    out[k].iterations = plastic[l] ? static_cast<int>(rm.iterations[l]) : 0;
    out[k].converged = true;
    if (damage_scalar[l]) {
      st.sigma_y = sy_increment[l];
      point_kernel::finish_plastic_step(m, sw, st, dp[l], dt, length[k], scale[l], rm.rate[l],
                                        heated[l] != 0);
      continue;
    }
    st.omega = omega_new[l];
    st.D = D_new[l];
    st.strength_scale = end_scale[l];
    st.sigma_y_static = sy_static_new[l];
    st.sigma_y = sy_new[l];
    st.sigma_y_peak = sy_peak_new[l];
    st.sigma_y_static_peak = sy_static_peak_new[l];
  }
}

}  // namespace

// SPLAT_BATCH_SINGLE_TARGET builds one variant for the compiler's flags
// instead (to check the SSE2 and AVX2 code on an AVX-512 machine by hand:
// see the batch test's header).
#ifdef SPLAT_BATCH_SINGLE_TARGET
#define SPLAT_BATCH_CLONES
#else
#define SPLAT_BATCH_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#endif

SPLAT_BATCH_CLONES void update_points(const Material& m, const MaterialConstants& mc,
                                      const ModelSwitches& sw, PointState* states, const int* index,
                                      std::size_t n, const Mat3* d_eps, const double* J_new,
                                      double dt, const double* length, PointUpdateResult* out) {
  for (std::size_t k0 = 0; k0 < n; k0 += W) {
    const int count = static_cast<int>(std::min<std::size_t>(W, n - k0));
    update_block(m, mc, sw, states, index, k0, count, d_eps, J_new, dt, length, out);
  }
}

}  // namespace splat
