#include "solver/material/point_update.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <variant>

#include "solver/common/isa.hpp"
#include "solver/material/damage.hpp"
#include "solver/material/elasticity.hpp"
#include "solver/material/eos.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/point_update_fast.hpp"
#include "solver/material/update_points_isa.hpp"

namespace splat {

MaterialConstants derive_constants(const Material& m) {
  MaterialConstants c;
  c.G = m.elastic.shear_modulus();
  c.K = m.elastic.bulk_modulus();
  c.rho0 = m.density;
  c.c_p = m.thermal.c_p;
  c.chi = m.thermal.heat_fraction;
  c.heating = c.rho0 * c.c_p > 0.0 ? c.chi / (c.rho0 * c.c_p) : 0.0;
  double K_wave = c.K;
  if (m.eos.model == EosModel::mie_gruneisen && m.eos.mie_gruneisen) {
    K_wave = std::max(c.K, c.rho0 * m.eos.mie_gruneisen->c0 * m.eos.mie_gruneisen->c0);
  }
  c.wave_speed = std::sqrt((K_wave + 4.0 * c.G / 3.0) / c.rho0);
  if (const auto* jc = std::get_if<JohnsonCookParams>(&m.strength)) c.jc_series = jc_series(*jc);
  return c;
}

namespace {

// The pressure and compression a strength law sees at the point.
PressureState pressure_state(const PointState& st) {
  return {st.p, 1.0 / st.J};
}

// The strength caches of a point (hardening, strength_scale, sigma_y_static)
// at its eps_p, T and D, and sigma_y at its eps_dot_p: for Johnson-Cook,
// A + B eps_p^n and (1 - D)(1 - T*^m) (its return and fast path use them);
// for any other law, its undamaged flow stress at zero plastic rate (and the
// point's pressure state) and 1 - D.
template <class Law>
void set_strength(const Law& law, const ModelSwitches& sw, PointState& st) {
  const PressureState ps = pressure_state(st);
  st.hardening = flow_stress(law, sw, st.eps_p, 0.0, st.T, ps).value;
  st.strength_scale = 1.0 - st.D;
  st.sigma_y_static = st.strength_scale * st.hardening;
  st.sigma_y = st.strength_scale * flow_stress(law, sw, st.eps_p, st.eps_dot_p, st.T, ps).value;
}

void set_strength(const JohnsonCookParams& jc, const ModelSwitches& sw, PointState& st) {
  st.hardening = jc_hardening(jc, st.eps_p);
  st.strength_scale = (1.0 - st.D) * jc_thermal_factor(jc, sw.thermal_softening, st.T);
  st.sigma_y_static =
      (1.0 - st.D) * johnson_cook_flow_stress(jc, sw, st.eps_p, st.eps_dot_p, st.T).value;
  st.sigma_y = st.sigma_y_static;
}

}  // namespace

void add_heat(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
              PointState& st, double q) {
  if (mc.rho0 * mc.c_p <= 0.0 || q == 0.0) return;
  st.e += q;
  st.T += q / (mc.rho0 * mc.c_p);
  if (const auto* jc = std::get_if<JohnsonCookParams>(&m.strength)) {
    const double rate = st.sigma_y_static > 0.0 ? st.sigma_y / st.sigma_y_static : 1.0;
    st.strength_scale = (1.0 - st.D) * jc_thermal_factor(*jc, sw.thermal_softening, st.T);
    st.sigma_y_static = st.strength_scale * st.hardening;
    st.sigma_y = st.sigma_y_static * rate;
  } else {
    std::visit([&](const auto& law) { set_strength(law, sw, st); }, m.strength);
  }
  st.sigma_y_static_peak = std::max(st.sigma_y_static_peak, st.sigma_y_static);
}

PointState initial_point_state(const Material& m, const ModelSwitches& sw, double T0, double D0) {
  PointState st;
  st.T = T0;
  st.D = sw.damage ? D0 : 0.0;
  std::visit([&](const auto& law) { set_strength(law, sw, st); }, m.strength);
  st.sigma_y_peak = st.sigma_y;
  st.sigma_y_static_peak = st.sigma_y_static;
  return st;
}

// From the invariants of the deviator s: with r = cos 3 phi =
// (3 sqrt(3) / 2) J3 / J2^(3/2), phi in [0, pi/3], the principal deviators
// are 2 sqrt(J2 / 3) cos(phi + 2 pi k / 3), so
//   sigma_1 - sigma_3 = 2 sqrt(J2 / 3) (3/2 c + sqrt(3)/2 sqrt(1 - c^2)),
// c = cos phi, the largest root of 4 c^3 - 3 c = r. c = cos(2/3 acos u) with
// u = sqrt((1 + r) / 2) is analytic in u on [0, 1]: a Chebyshev series of
// degree 16 in x = 2 u - 1 (coefficients by interpolation at 48 Chebyshev
// nodes) gives it to 2e-15, without the atan2, sin and cos of Eigen's closed
// form (computeDirect): 19 ns a call against 60 ns (bench_material_update
// --benchmark_filter=max_shear). Near a double eigenvalue (r = +-1) both
// forms lose precision alike, to about 1e-8 of tau_max: r carries the gap
// squared.
double max_shear_stress(const Mat3& sigma) {
  const double m = sigma.trace() / 3.0;
  const double a = sigma(0, 0) - m, b = sigma(1, 1) - m, c = sigma(2, 2) - m;
  const double d = 0.5 * (sigma(0, 1) + sigma(1, 0)), e = 0.5 * (sigma(0, 2) + sigma(2, 0)),
               f = 0.5 * (sigma(1, 2) + sigma(2, 1));
  const double J2 = 0.5 * (a * a + b * b + c * c) + d * d + e * e + f * f;
  if (!(J2 > 0.0)) return 0.0;
  const double J3 = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e);
  const double root_J2 = std::sqrt(J2);
  const double r = std::clamp(1.5 * std::sqrt(3.0) * J3 / (J2 * root_J2), -1.0, 1.0);
  const double x = 2.0 * std::sqrt(0.5 * (1.0 + r)) - 1.0;
  // The series as a polynomial in x (converted exactly, then rounded),
  // evaluated by Estrin's scheme: a dependency chain of 5 products instead
  // of Clenshaw's 16 steps.
  static constexpr double p[17] = {
      0.76604444311897835,     0.2474090663228358,      -0.015509188436523267,
      0.0024663528158471353,   -0.00050412469054537479, 0.00011642544288496352,
      -2.891993905033511e-05,  7.5411390165018117e-06,  -2.0358683053463738e-06,
      5.6395856103582287e-07,  -1.5952018372900056e-07, 4.6205665663971253e-08,
      -1.3422114382895718e-08, 3.5833617554696194e-09,  -1.0865051081054844e-09,
      5.3182702686171979e-10,  -1.5575096767861396e-10};
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  double q[8];
  for (int k = 0; k < 8; ++k) q[k] = p[2 * k] + p[2 * k + 1] * x;
  const double r0 = q[0] + q[1] * x2, r1 = q[2] + q[3] * x2, r2 = q[4] + q[5] * x2,
               r3 = q[6] + q[7] * x2;
  const double poly = (r0 + r1 * x4) + (r2 + r3 * x4 + p[16] * x8) * x8;
  const double cos_phi = std::min(poly, 1.0);
  const double sin_phi = std::sqrt(std::max(1.0 - cos_phi * cos_phi, 0.0));
  return root_J2 / std::sqrt(3.0) * (1.5 * cos_phi + 0.5 * std::sqrt(3.0) * sin_phi);
}

namespace {

// Damage initiation and evolution for the plastic increment dp of this step.
void update_damage(const Material& m, const ModelSwitches& sw, PointState& st, double dp, double dt,
                   double length) {
  const DamageParams& dm = m.damage;
  if (!sw.damage || dm.initiation == DamageInitiation::none || dp <= 0.0) return;

  const double eps_dot = dp / dt;
  double dp_after_init = 0.0;
  if (st.eps_p_init < 0.0) {
    const double q = von_mises(st.s);
    double eps_f = 0.0;
    if (dm.initiation == DamageInitiation::johnson_cook) {
      const double eta = q > 0.0 ? -st.p / q : 0.0;
      eps_f = jc_failure_strain(dm.jc, strength_references(m.strength), sw.rate_hardening,
                                sw.thermal_softening, eta, eps_dot, st.T);
    } else {
      const double theta = shear_stress_ratio(dm.shear.k_s, st.p, q, max_shear_stress(st.cauchy()));
      eps_f = shear_failure_strain(dm.shear, theta, eps_dot);
    }
    const double omega_old = st.omega;
    st.omega += dp / eps_f;
    if (st.omega < 1.0) return;
    // Initiation inside this increment: the part of dp past omega = 1 drives
    // the evolution.
    const double frac_before = (1.0 - omega_old) / (st.omega - omega_old);
    st.eps_p_init = st.eps_p - dp + frac_before * dp;
    dp_after_init = (1.0 - frac_before) * dp;
  } else {
    dp_after_init = dp;
  }

  double D = st.D;
  switch (dm.evolution) {
    case DamageEvolution::instant:
      D = dm.D_max;
      break;
    case DamageEvolution::plastic_strain: {
      const double span = dm.eps_p_max - st.eps_p_init;
      D = span > 0.0 ? D + dp_after_init / span : dm.D_max;
      break;
    }
    case DamageEvolution::fracture_energy:
      D += dm.D_max * st.sigma_y * dp_after_init * length / dm.G_f;
      break;
  }
  st.D = std::min(std::max(D, st.D), dm.D_max);
}

}  // namespace

namespace {

PointFields<double> point_fields(const PointState& st) {
  PointFields<double> f;
  for (int k = 0; k < 6; ++k) f.s[k] = st.s(sym_row[k], sym_col[k]);
  for_each_point_field(f, [&](double& v, double PointState::*field) { v = st.*field; });
  return f;
}

void set_point_fields(PointFields<double>& f, PointState& st) {
  for (int k = 0; k < 6; ++k) {
    st.s(sym_row[k], sym_col[k]) = f.s[k];
    st.s(sym_col[k], sym_row[k]) = f.s[k];
  }
  for_each_point_field(f, [&](double& v, double PointState::*field) { st.*field = v; });
}

}  // namespace

PointUpdateResult update_point(const Material& m, const MaterialConstants& mc,
                               const ModelSwitches& sw, PointState& st, const Mat3& d_eps,
                               double J_new, double dt, double length) {
  // Most steps: point_update_fast (the same choice and bits as the lanes of
  // update_points and of the FE element loop).
  if (std::holds_alternative<JohnsonCookParams>(m.strength) && is_symmetric(st.s) &&
      is_symmetric(d_eps)) {
    PointFields<double> f = point_fields(st);
    double de[6];
    for (int k = 0; k < 6; ++k) de[k] = d_eps(sym_row[k], sym_col[k]);
    double evaluations = 0.0;
    if (point_update_fast(m, mc, sw, f, de, J_new, dt, evaluations)) {
      set_point_fields(f, st);
      return {static_cast<int>(evaluations), true};
    }
  }
  return update_point_general(m, mc, sw, st, d_eps, J_new, dt, length);
}

namespace {

// The plastic increment of a step and the strength terms at its end.
struct PlasticReturn {
  double delta_eps_p = 0.0;  // plastic strain increment, -
  double sigma_y = 0.0;      // damaged flow stress of the increment, Pa
  double hard = 0.0;         // Johnson-Cook: A + B eps_p^n at the end of the step, Pa
  double rate = 1.0;         // Johnson-Cook: 1 + C ln(eps_dot_p / eps_dot_0) of the increment, -
  int iterations = 0;        // return-mapping iterations
  bool converged = true;
};

// Any law: the general radial return (strength_model.hpp) at the start
// temperature, damage and pressure state.
template <class Law>
PlasticReturn plastic_return(const Law& law, const MaterialConstants&, const ModelSwitches& sw,
                             const PointState& st, double q_trial, double G_d, double dt) {
  const LawReturn r =
      law_return(law, sw, q_trial, G_d, 1.0 - st.D, st.eps_p, dt, st.T, pressure_state(st));
  return {r.delta_eps_p, r.sigma_y, 0.0, 1.0, r.iterations, r.converged};
}

// Johnson-Cook: its own return, seeded by the previous step's increment and
// rate factor and the cached hardening and scale (johnson_cook_return).
PlasticReturn plastic_return(const JohnsonCookParams& jc, const MaterialConstants& mc,
                             const ModelSwitches& sw, const PointState& st, double q_trial,
                             double G_d, double dt) {
  const double scale = st.strength_scale;
  // After a plastic step sigma_y = sigma_y_static R(eps_dot_p): the rate
  // factor at the guess (the return's expansions start from it).
  const double rate_guess =
      st.eps_dot_p > 0.0 && st.sigma_y_static > 0.0 ? st.sigma_y / st.sigma_y_static : 0.0;
  const ReturnMapResult rm =
      johnson_cook_return(jc, sw.rate_hardening, q_trial, G_d, st.eps_p, dt, scale, st.hardening,
                          st.eps_dot_p * dt, rate_guess, &mc.jc_series);
  return {rm.delta_eps_p, scale * rm.hard_rate, rm.hard, rm.rate, rm.iterations, rm.converged};
}

// Any law: the strength caches after a plastic step moved eps_p, T or D.
template <class Law>
void end_strength(const Law& law, const MaterialConstants&, const ModelSwitches& sw, PointState& st,
                  const PlasticReturn&, double, double, bool) {
  set_strength(law, sw, st);
}

// Johnson-Cook: A + B eps_p^n from the return; an undamaged point's thermal
// factor carried over a small heating step by a series
// (jc_thermal_factor_after_heating).
void end_strength(const JohnsonCookParams& jc, const MaterialConstants& mc, const ModelSwitches& sw,
                  PointState& st, const PlasticReturn& ret, double T_old, double D_old,
                  bool heated) {
  const double scale = st.strength_scale;
  st.hardening = ret.hard;
  double end_scale = scale;
  if (heated && st.D == 0.0 && D_old == 0.0 && sw.thermal_softening) {
    end_scale = jc_thermal_factor_after_heating(jc, mc.jc_series, scale, T_old, st.T);
  } else if (heated || st.D != D_old) {
    end_scale = (1.0 - st.D) * jc_thermal_factor(jc, sw.thermal_softening, st.T);
  }
  st.strength_scale = end_scale;
  st.sigma_y_static = end_scale * st.hardening;
  st.sigma_y = st.sigma_y_static * ret.rate;
}

// The general update with the strength law `law` (update_point_general).
template <class Law>
PointUpdateResult update_with_law(const Law& law, const Material& m, const MaterialConstants& mc,
                                  const ModelSwitches& sw, PointState& st, const Mat3& d_eps,
                                  double J_new, double dt, double length) {
  PointUpdateResult result;
  const double keep = 1.0 - st.D;
  const double G_d = keep * mc.G;
  const Mat3 sigma_old = st.cauchy();
  const double J_old = st.J;

  // Elastic predictor for the deviator, then radial return. The yield test
  // compares squares (sigma_y_static >= 0): an elastic step takes no square
  // root.
  Mat3 s = st.s + 2.0 * G_d * deviator(d_eps);
  const double q_trial_sq = 1.5 * s.squaredNorm();
  double dp = 0.0;
  PlasticReturn ret;
  if (q_trial_sq > st.sigma_y_static * st.sigma_y_static) {
    const double q_trial = std::sqrt(q_trial_sq);
    ret = plastic_return(law, mc, sw, st, q_trial, G_d, dt);
    dp = ret.delta_eps_p;
    result.iterations = ret.iterations;
    result.converged = ret.converged;
    // Radial scaling of the trial deviator onto the yield surface.
    s *= std::max(q_trial - 3.0 * G_d * dp, 0.0) / q_trial;
  }
  st.s = s;
  st.eps_p += dp;
  st.eps_dot_p = dp / dt;

  // Pressure from the EOS at J_new, with the energy term implicit in p:
  // e_new = e_old + J_mid/2 (sigma_old + sigma_new) : d_eps, sigma = s - p I.
  st.J = J_new;
  const double J_mid = 0.5 * (J_old + J_new);
  const double tr = d_eps.trace();
  const double e_star =
      st.e +
      0.5 * J_mid * ((sigma_old.array() * d_eps.array()).sum() + (s.array() * d_eps.array()).sum());
  const EosSplit eos = eos_split(m.eos, mc.K, mc.rho0, J_new);
  // (No division where there is no energy term: the linear EOS.)
  const double p_explicit = eos.p_cold + eos.gamma_e * e_star;
  double p = eos.gamma_e != 0.0 ? p_explicit / (1.0 + 0.5 * eos.gamma_e * J_mid * tr) : p_explicit;
  p = apply_tension_damage(p, st.D);
  st.p = p;
  st.e = e_star - 0.5 * J_mid * p * tr;

  // Adiabatic heating: a fraction chi of the plastic work per unit current
  // volume, sigma_y dp, raises the temperature of mass rho = rho0 / J.
  if (dp > 0.0) {
    st.sigma_y = ret.sigma_y;          // flow stress of this increment
    const double w = st.sigma_y * dp;  // plastic work, J/m^3 of current volume
    st.plastic_work += J_new * w;
    const bool heated = sw.adiabatic_heating && w > 0.0;
    const double T_old = st.T;
    if (heated) st.T += mc.heating * (w * J_new);
    const double D_old = st.D;
    update_damage(m, sw, st, dp, dt, length);
    // Temperature or damage moved: the strength at the end state changes.
    end_strength(law, mc, sw, st, ret, T_old, D_old, heated);
  } else {
    // The pressure and eta moved: a law that depends on them needs its
    // caches at the end state (the others' did not change).
    if constexpr (pressure_dependent<Law>()) set_strength(law, sw, st);
    st.sigma_y = st.sigma_y_static;  // no plastic rate: no rate hardening
  }
  st.sigma_y_peak = std::max(st.sigma_y_peak, st.sigma_y);
  st.sigma_y_static_peak = std::max(st.sigma_y_static_peak, st.sigma_y_static);
  return result;
}

}  // namespace

// The one place the strength law is chosen.
PointUpdateResult update_point_general(const Material& m, const MaterialConstants& mc,
                                       const ModelSwitches& sw, PointState& st, const Mat3& d_eps,
                                       double J_new, double dt, double length) {
  return std::visit(
      [&](const auto& law) {
        return update_with_law(law, m, mc, sw, st, d_eps, J_new, dt, length);
      },
      m.strength);
}

// Groups of 8 points in lanes, compiled once per instruction set
// (update_points_isa.cpp), the set chosen at run time.
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out) {
  auto* const run = [] {
    switch (active_isa()) {
      case Isa::x86_64_v4:
        return &isa_v4::update_points;
      case Isa::x86_64_v3:
        return &isa_v3::update_points;
      case Isa::baseline:
        break;
    }
    return &isa_baseline::update_points;
  }();
  run(m, mc, sw, states, index, n, d_eps, J_new, dt, length, out);
}

}  // namespace splat
