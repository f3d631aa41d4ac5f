// Material-point checks of a strength law against its closed form, shared by
// the verification tests of each law. A `Law` gives flow(eps_p, rate, T) and
// slope(eps_p, rate, T) = d flow / d eps_p (Pa; rate in 1/s, T in K).
#pragma once

#include <gtest/gtest.h>

#include "solver/material/material_point_driver.hpp"

namespace splat::test_support {

// Uniaxial-stress compression of `m` at `rate` (1/s) to the true strain
// `max_strain` (negative) in `steps`, from the law's reference temperature,
// damage off.
inline MaterialPointRequest compression(const Material& m, double rate, double max_strain,
                                        int steps) {
  MaterialPointRequest r;
  r.material = m;
  r.mode = LoadingMode::uniaxial_stress;
  r.strain_rate = rate;
  r.max_strain = max_strain;
  r.steps = steps;
  r.temperature = strength_references(m.strength).T_ref;
  r.switches.damage = false;
  return r;
}

// Temperature after adiabatic plastic straining to eps_p from T0: dT / d eps_p
// = beta sigma(eps_p, T), beta = chi / (rho c_p), by classical Runge-Kutta in
// `steps` equal steps.
template <class Flow>
double adiabatic_temperature(Flow sigma, double T0, double beta, double eps_p, int steps) {
  const double h = eps_p / steps;
  double T = T0;
  for (int i = 0; i < steps; ++i) {
    const double e = i * h;
    const double k1 = beta * sigma(e, T);
    const double k2 = beta * sigma(e + 0.5 * h, T + 0.5 * h * k1);
    const double k3 = beta * sigma(e + 0.5 * h, T + 0.5 * h * k2);
    const double k4 = beta * sigma(e + h, T + h * k3);
    T += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return T;
}

// The plastic part of the imposed rate once the stress follows the curve:
// rate E / (E + H), H the curve's slope.
template <class Law>
double plastic_rate(const Law& law, double E, double eps_p, double rate, double T) {
  return rate * E / (E + law.slope(eps_p, rate, T));
}

// Isothermal run (heating off): from eps_p = eps_from on, every row's stress
// within 0.1 % of flow(eps_p, plastic rate, T0); at least 1000 rows checked.
template <class Law>
void expect_isothermal_curve(const Law& law, MaterialPointRequest r, double eps_from) {
  r.switches.adiabatic_heating = false;
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged) << res.message;
  const double E = r.material.elastic.E, T = r.temperature;
  int checked = 0;
  for (const MaterialPointRow& row : res.rows) {
    if (row.plastic_strain < eps_from) continue;
    const double rate_p = plastic_rate(law, E, row.plastic_strain, r.strain_rate, T);
    const double expected = law.flow(row.plastic_strain, rate_p, T);
    ASSERT_NEAR(-row.stress, expected, 1e-3 * expected)
        << "rate " << r.strain_rate << " T0 " << T << " eps_p " << row.plastic_strain;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

// Adiabatic run: the temperature within 0.5 % of the rise plus 0.01 K of the
// work ODE (the kernel heats with the start-of-step flow stress, on the
// current volume), the stress within 0.5 % of flow(eps_p, plastic rate,
// T(eps_p)) past eps_p = 0.01, and a rise above 50 K.
template <class Law>
void expect_adiabatic_curve(const Law& law, const MaterialPointRequest& r) {
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged) << res.message;
  const Material& m = r.material;
  const double beta = m.thermal.heat_fraction / (m.density * m.thermal.c_p);
  const double rate = r.strain_rate, T0 = r.temperature;
  auto sigma = [&](double e, double T) { return law.flow(e, rate, T); };
  for (std::size_t i = 1; i < res.rows.size(); i += 10) {
    const MaterialPointRow& row = res.rows[i];
    const double T = adiabatic_temperature(sigma, T0, beta, row.plastic_strain, 200);
    const double rise = T - T0;
    ASSERT_NEAR(row.temperature - T0, rise, 5e-3 * rise + 0.01) << "row " << i;
    if (row.plastic_strain > 0.01) {
      const double rate_p = plastic_rate(law, m.elastic.E, row.plastic_strain, rate, T);
      const double expected = law.flow(row.plastic_strain, rate_p, T);
      ASSERT_NEAR(-row.stress, expected, 5e-3 * expected) << "row " << i;
    }
  }
  EXPECT_GT(res.rows.back().temperature - T0, 50.0);
}

}  // namespace splat::test_support
