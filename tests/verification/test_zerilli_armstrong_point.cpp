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
#include "support/flow_curve_checks.hpp"

namespace splat {
namespace {

exact::ZaCurve curve_of(const Material& m) {
  const ZerilliArmstrongParams& z = std::get<ZerilliArmstrongParams>(m.strength);
  return {z.C0, z.C2, z.C3, z.C4, z.eps_dot_0, z.T_melt};
}

// The law's closed form, for the shared checks.
struct Law {
  exact::ZaCurve c;
  double flow(double eps_p, double rate, double T) const {
    return exact::za_flow_stress(c, eps_p, rate, T);
  }
  double slope(double eps_p, double rate, double T) const {
    return exact::za_hardening_slope(c, eps_p, rate, T);
  }
};

MaterialPointRequest compression(double rate, double max_strain, int steps) {
  return test_support::compression(
      load_material(std::string(SPLAT_SOURCE_DIR) + "/tests/data/za_test_parameters.json"), rate,
      max_strain, steps);
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
      r.temperature += T0_offset;
      test_support::expect_isothermal_curve(Law{curve_of(r.material)}, r, 0.01);
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
  const MaterialPointRequest r = compression(1e4, -1.0, 4000);
  test_support::expect_adiabatic_curve(Law{curve_of(r.material)}, r);
}

}  // namespace
}  // namespace splat
