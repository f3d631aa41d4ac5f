// Material-point verification of the Zerilli-Armstrong FCC law
// (solver/material/zerilli_armstrong.hpp) through `splat mat-point`'s driver
// against the closed form of the published equation
// (tests/exact/zerilli_armstrong_closed_form.hpp), for OFHC copper
// (tests/data/za_test_parameters.json: the constants commonly quoted for OFHC
// copper, not checked against the paper, hence not in the library). Each test states its tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "exact/zerilli_armstrong_closed_form.hpp"
#include "solver/input/material_io.hpp"
#include "solver/material/material_point_driver.hpp"

namespace splat {
namespace {

exact::ZaCurve curve_of(const Material& m) {
  const ZerilliArmstrongParams& z = std::get<ZerilliArmstrongParams>(m.strength);
  return {z.C0, z.C2, z.C3, z.C4, z.eps_dot_0, z.T_melt};
}

MaterialPointRequest compression(double rate, double max_strain, int steps) {
  MaterialPointRequest r;
  r.material = load_material(std::string(SPLAT_SOURCE_DIR) + "/tests/data/za_test_parameters.json");
  r.mode = LoadingMode::uniaxial_stress;
  r.strain_rate = rate;
  r.max_strain = max_strain;
  r.steps = steps;
  r.temperature = strength_references(r.material.strength).T_ref;
  r.switches.damage = false;
  return r;
}

// Isothermal uniaxial stress follows sigma(eps_p, rate_p, T) from quasi-static
// to cold-spray rates (1e-3 to 1e8 /s; below eps_dot_0 = 1/s the law counts
// 1/s) and from room temperature to 850 K. The imposed rate splits into an
// elastic and a plastic part, rate = sigma_dot / E + rate_p with sigma_dot =
// H rate_p, so the reference uses rate_p = rate E / (E + H), H the slope d
// sigma / d eps_p. Tolerance 0.1 % of the flow stress, from eps_p = 0.01 on.
TEST(uniaxial_zerilli_armstrong, isothermal_curve_at_several_rates_and_temperatures) {
  for (double rate : {1e-3, 1.0, 1e3, 1e6, 1e8}) {
    for (double T0_offset : {0.0, 300.0, 550.0}) {
      MaterialPointRequest r = compression(rate, -0.6, 1200);
      r.switches.adiabatic_heating = false;
      r.temperature += T0_offset;
      const MaterialPointResult res = run_material_point(r);
      ASSERT_TRUE(res.converged) << res.message;
      const exact::ZaCurve c = curve_of(r.material);
      const double E = r.material.elastic.E;
      int checked = 0;
      for (const MaterialPointRow& row : res.rows) {
        if (row.plastic_strain < 0.01) continue;
        const double H = exact::za_hardening_slope(c, row.plastic_strain, rate, r.temperature);
        const double rate_p = rate * E / (E + H);
        const double expected = exact::za_flow_stress(c, row.plastic_strain, rate_p, r.temperature);
        ASSERT_NEAR(-row.stress, expected, 1e-3 * expected)
            << "rate " << rate << " T0 " << r.temperature << " eps_p " << row.plastic_strain;
        ++checked;
      }
      EXPECT_GT(checked, 1000);
    }
  }
}

// Adiabatic uniaxial stress at 1e4 /s to a true strain of 1: the temperature
// follows dT / d eps_p = chi sigma / (rho c_p) (solved by Runge-Kutta in the
// closed-form module) and the stress is sigma(eps_p, rate, T(eps_p)). The
// kernel heats with the flow stress at the start of each step, on the
// current volume (rho differs from rho0 by the elastic volume change, below
// 0.1 %), and takes rate_p for the rate (below 0.1 % of the stress past eps_p
// = 0.01): tolerance 0.5 % of the rise plus 0.01 K, and 0.5 % of the stress.
TEST(uniaxial_zerilli_armstrong, adiabatic_heating_follows_the_work_ode) {
  const double rate = 1e4;
  const MaterialPointRequest r = compression(rate, -1.0, 4000);
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged) << res.message;
  const Material& m = r.material;
  const exact::ZaCurve c = curve_of(m);
  const double beta = m.thermal.heat_fraction / (m.density * m.thermal.c_p);
  for (std::size_t i = 1; i < res.rows.size(); i += 10) {
    const MaterialPointRow& row = res.rows[i];
    const double T =
        exact::za_adiabatic_temperature(c, rate, r.temperature, beta, row.plastic_strain, 200);
    const double rise = T - r.temperature;
    ASSERT_NEAR(row.temperature - r.temperature, rise, 5e-3 * rise + 0.01) << "row " << i;
    if (row.plastic_strain > 0.01) {
      const double expected = exact::za_flow_stress(c, row.plastic_strain, rate, T);
      ASSERT_NEAR(-row.stress, expected, 5e-3 * expected) << "row " << i;
    }
  }
  EXPECT_GT(res.rows.back().temperature - r.temperature, 50.0);
}

}  // namespace
}  // namespace splat
