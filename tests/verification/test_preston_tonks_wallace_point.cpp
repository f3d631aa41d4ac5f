// Material-point verification of the Preston-Tonks-Wallace law
// (solver/material/preston_tonks_wallace.hpp) through `splat mat-point`'s
// driver against the closed form of the published equations
// (tests/exact/preston_tonks_wallace_closed_form.hpp), for OFHC copper
// (materials/cu-ofhc-ptw.json) and for tantalum (materials/ta-ptw.json,
// p = 0: the law's p -> 0 limit). Each test states its tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "exact/preston_tonks_wallace_closed_form.hpp"
#include "solver/input/material_io.hpp"
#include "solver/material/material_point_driver.hpp"
#include "solver/material/preston_tonks_wallace.hpp"
#include "support/flow_curve_checks.hpp"

namespace splat {
namespace {

exact::PtwCurve curve_of(const Material& m) {
  const PrestonTonksWallaceParams& w = std::get<PrestonTonksWallaceParams>(m.strength);
  return {w.theta, w.p,  w.s0,   w.s_inf, w.kappa, w.gamma, w.y0,        w.y_inf,
          w.y1,    w.y2, w.beta, w.G,     w.rho,   w.M,     w.eps_dot_0, w.T_melt};
}

// The law's closed form, for the shared checks.
struct Law {
  exact::PtwCurve c;
  double flow(double eps_p, double rate, double T) const {
    return exact::ptw_flow_stress(c, eps_p, rate, T);
  }
  double slope(double eps_p, double rate, double T) const {
    return exact::ptw_hardening_slope(c, eps_p, rate, T);
  }
};

MaterialPointRequest compression(double rate, double max_strain, int steps) {
  return test_support::compression(load_material("cu-ofhc-ptw"), rate, max_strain, steps);
}

// Isothermal uniaxial stress follows sigma(eps_p, rate_p, T) from
// quasi-static to cold-spray rates (1e-3 to 1e9 /s; below eps_dot_0 = 1/s
// the law counts 1/s; past ~1e8 /s copper enters the overdriven-shock
// branch) and from room temperature to 850 K. The reference uses the
// plastic rate rate_p = rate E / (E + H), H the slope d sigma / d eps_p (the
// elastic part of the imposed rate). That relation ignores the transient
// after yield in which the plastic rate catches up with the imposed one: it
// lasts a plastic strain of about m sigma / E, m = d ln sigma / d ln eps_dot
// (0.25 in the overdriven-shock branch, 0.003 of strain at 1e9 /s), so the
// check starts at eps_p = 0.05. Tolerance 0.1 % of the flow stress.
TEST(uniaxial_preston_tonks_wallace, isothermal_curve_at_several_rates_and_temperatures) {
  for (double rate : {1e-3, 1.0, 1e3, 1e6, 1e8, 1e9}) {
    for (double T0_offset : {0.0, 300.0, 550.0}) {
      MaterialPointRequest r = compression(rate, -0.6, 1200);
      r.temperature += T0_offset;
      test_support::expect_isothermal_curve(Law{curve_of(r.material)}, r, 0.05);
    }
  }
}

// Adiabatic uniaxial stress at 1e4 /s to a true strain of 1: the temperature
// follows dT / d eps_p = chi sigma / (rho c_p) (Runge-Kutta in the
// closed-form module) and the stress is sigma(eps_p, rate, T(eps_p)).
// The stress reference takes the plastic rate rate_p = rate E / (E + H) as
// the isothermal test (the yield branch near onset goes as rate^0.575).
// Tolerances as for the other laws: 0.5 % of the rise plus 0.01 K (heating
// with the start-of-step flow stress, on the current volume), and 0.5 % of
// the stress.
TEST(uniaxial_preston_tonks_wallace, adiabatic_heating_follows_the_work_ode) {
  const MaterialPointRequest r = compression(1e4, -1.0, 4000);
  test_support::expect_adiabatic_curve(Law{curve_of(r.material)}, r);
}

// The kernel at p = 0 is the closed form of the limit p -> 0,
// tau = tau_s - (tau_s - tau_y) exp(-theta psi / (tau_s - tau_y)), and its
// slope theta exp(-theta psi / (tau_s - tau_y)), from the quasi-static to the
// overdriven-shock branch (1 to 1e9 /s) and from room temperature to 2000 K,
// to 1e-12 of the flow stress.
TEST(preston_tonks_wallace_p_zero, kernel_is_the_closed_form_of_the_limit) {
  const PrestonTonksWallaceParams w =
      std::get<PrestonTonksWallaceParams>(load_material("ta-ptw").strength);
  ASSERT_EQ(w.p, 0.0);
  const Law law{curve_of(load_material("ta-ptw"))};
  const ModelSwitches sw;
  for (double rate : {1.0, 1e3, 1e6, 1e9}) {
    for (double T : {300.0, 800.0, 2000.0}) {
      for (double psi : {0.0, 0.01, 0.1, 0.5, 2.0}) {
        const FlowStress f = flow_stress(w, sw, psi, rate, T, PressureState{});
        const double expected = law.flow(psi, rate, T);
        EXPECT_NEAR(f.value, expected, 1e-12 * expected) << rate << " /s, " << T << " K, " << psi;
        const double slope = law.slope(psi, rate, T);
        EXPECT_NEAR(f.d_eps_p, slope, 1e-12 * expected) << rate << " /s, " << T << " K, " << psi;
      }
    }
  }
}

// The general formula joins the limit: with p = 1e-6 instead of 0 the kernel
// and the closed form's general branch (a separate derivation: its
// logarithm, not the limit) both stay within 1e-5 of the p = 0 flow stress
// (the difference is of order p), and at p = 1e-2 already differ by more
// than 1e-5 at eps_p = 0.5 (so the comparison can tell the two apart).
TEST(preston_tonks_wallace_p_zero, small_p_tends_to_the_limit) {
  const Material ta = load_material("ta-ptw");
  const PrestonTonksWallaceParams w0 = std::get<PrestonTonksWallaceParams>(ta.strength);
  const exact::PtwCurve c0 = curve_of(ta);
  const ModelSwitches sw;
  for (double rate : {1.0, 1e3, 1e6}) {
    for (double psi : {0.05, 0.5, 2.0}) {
      const double limit = exact::ptw_flow_stress(c0, psi, rate, 300.0);
      PrestonTonksWallaceParams w = w0;
      w.p = 1e-6;
      exact::PtwCurve c = c0;
      c.p = 1e-6;
      EXPECT_NEAR(flow_stress(w, sw, psi, rate, 300.0, PressureState{}).value, limit, 1e-5 * limit);
      EXPECT_NEAR(exact::ptw_flow_stress(c, psi, rate, 300.0), limit, 1e-5 * limit);
    }
  }
  exact::PtwCurve c = c0;
  c.p = 1e-2;
  const double limit = exact::ptw_flow_stress(c0, 0.5, 1.0, 300.0);
  EXPECT_GT(std::abs(exact::ptw_flow_stress(c, 0.5, 1.0, 300.0) - limit), 1e-5 * limit);
}

// Tantalum (p = 0) through the driver: isothermal uniaxial stress follows
// sigma(eps_p, rate_p, T) from quasi-static to cold-spray rates and from room
// temperature to 1300 K, from eps_p = 0.05 (as for copper), to 0.1 %.
TEST(uniaxial_preston_tonks_wallace, tantalum_isothermal_curve_at_several_rates_and_temperatures) {
  for (double rate : {1e-3, 1.0, 1e3, 1e6, 1e8}) {
    for (double T0_offset : {0.0, 300.0, 1000.0}) {
      MaterialPointRequest r = test_support::compression(load_material("ta-ptw"), rate, -0.6, 1200);
      r.temperature += T0_offset;
      test_support::expect_isothermal_curve(Law{curve_of(r.material)}, r, 0.05);
    }
  }
}

// Tantalum, adiabatic uniaxial stress at 1e4 /s to a true strain of 1, with
// the tolerances of the copper test.
TEST(uniaxial_preston_tonks_wallace, tantalum_adiabatic_heating_follows_the_work_ode) {
  const MaterialPointRequest r =
      test_support::compression(load_material("ta-ptw"), 1e4, -1.0, 4000);
  test_support::expect_adiabatic_curve(Law{curve_of(r.material)}, r);
}

}  // namespace
}  // namespace splat
