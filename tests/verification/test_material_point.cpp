// Material-point verification: the driver against closed forms of the
// published equations (tests/exact/johnson_cook_closed_form.hpp). Each test
// states its tolerance; scripts/mutation_check.sh breaks the kernels on
// purpose and confirms that each test then fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "exact/johnson_cook_closed_form.hpp"
#include "solver/input/material_io.hpp"
#include "solver/material/elasticity.hpp"
#include "solver/material/material_point_driver.hpp"

namespace splat {
namespace {

exact::JcCurve curve_of(const Material& m) {
  const JohnsonCookParams& j = std::get<JohnsonCookParams>(m.strength);
  return {j.A, j.B, j.n, j.C, j.eps_dot_0, j.m, j.T_ref, j.T_melt};
}

MaterialPointRequest request(const std::string& material, LoadingMode mode, double rate,
                             double max_strain, int steps) {
  MaterialPointRequest r;
  r.material = load_material(material);
  r.mode = mode;
  r.strain_rate = rate;
  r.max_strain = max_strain;
  r.steps = steps;
  r.temperature = std::get<JohnsonCookParams>(r.material.strength).T_ref;
  return r;
}

// Isothermal uniaxial stress follows the Johnson-Cook curve sigma(eps_p,
// rate_p, T). In uniaxial stress the imposed rate splits into an elastic and a
// plastic part, rate = sigma_dot / E + rate_p with sigma_dot = H rate_p, so the
// reference uses rate_p = rate E / (E + H), H the Johnson-Cook slope
// d sigma / d eps_p. Tolerance 0.1 % of the flow stress.
TEST(uniaxial_johnson_cook, isothermal_curve_at_several_rates_and_temperatures) {
  for (const char* name : {"cu-thesis", "al-thesis", "ti6al4v-thesis"}) {
    for (double rate : {1e-3, 1.0, 1e3, 1e6}) {
      for (double T0_offset : {0.0, 300.0, 550.0}) {
        MaterialPointRequest r = request(name, LoadingMode::uniaxial_stress, rate, -0.6, 1200);
        r.switches.adiabatic_heating = false;
        r.switches.damage = false;
        r.temperature += T0_offset;
        const MaterialPointResult res = run_material_point(r);
        ASSERT_TRUE(res.converged) << res.message;
        const exact::JcCurve c = curve_of(r.material);
        int checked = 0;
        for (const MaterialPointRow& row : res.rows) {
          if (row.plastic_strain < 0.01) continue;
          const double H = exact::jc_hardening_slope(c, row.plastic_strain, rate, r.temperature);
          const double rate_p = rate * r.material.elastic.E / (r.material.elastic.E + H);
          const double expected =
              exact::jc_flow_stress(c, row.plastic_strain, rate_p, r.temperature);
          ASSERT_NEAR(-row.stress, expected, 1e-3 * expected)
              << name << " rate " << rate << " T0 " << r.temperature << " eps_p "
              << row.plastic_strain;
          ++checked;
        }
        EXPECT_GT(checked, 1000);
      }
    }
  }
}

// Before yield, uniaxial stress is E times the (logarithmic) strain exactly
// for the log-volumetric EOS with the hypo-elastic deviator; 1e-9 relative.
TEST(uniaxial_johnson_cook, elastic_slope_is_youngs_modulus) {
  MaterialPointRequest r = request("cu-thesis", LoadingMode::uniaxial_stress, 1.0, 5e-4, 50);
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged);
  for (const MaterialPointRow& row : res.rows) {
    ASSERT_EQ(row.plastic_strain, 0.0);
    ASSERT_NEAR(row.stress, r.material.elastic.E * row.strain, 1e-9 * r.material.elastic.E * 5e-4);
  }
}

// The temperature rise equals heat_fraction times the plastic work per unit
// volume over rho c_p. The work is integrated independently from the CSV
// columns (trapezoid of stress over plastic strain); rho differs from rho0 by
// the elastic volume change (< 0.1 %) and the trapezoid differs from the
// kernel's end-of-step rule by O(1/steps): tolerance 0.5 % of the rise plus
// 0.01 K. The stress must also follow the Johnson-Cook curve at the row's own
// temperature (0.5 %).
TEST(adiabatic_heating, temperature_rise_matches_plastic_work) {
  for (const char* name : {"cu-thesis", "al-thesis", "steel-hopkinson"}) {
    MaterialPointRequest r = request(name, LoadingMode::uniaxial_stress, 1e4, -1.0, 4000);
    r.switches.damage = false;
    const MaterialPointResult res = run_material_point(r);
    ASSERT_TRUE(res.converged) << res.message;
    const Material& m = r.material;
    const exact::JcCurve c = curve_of(m);
    double work = 0.0;
    for (std::size_t i = 1; i < res.rows.size(); ++i) {
      const MaterialPointRow& a = res.rows[i - 1];
      const MaterialPointRow& b = res.rows[i];
      work +=
          0.5 * (std::abs(a.stress) + std::abs(b.stress)) * (b.plastic_strain - a.plastic_strain);
      const double dT_expected = m.thermal.heat_fraction * work / (m.density * m.thermal.c_p);
      const double dT = b.temperature - r.temperature;
      ASSERT_NEAR(dT, dT_expected, 5e-3 * dT_expected + 0.01) << name << " row " << i;
      if (b.plastic_strain > 0.01) {
        const double expected = exact::jc_flow_stress(c, b.plastic_strain, 1e4, b.temperature);
        ASSERT_NEAR(-b.stress, expected, 5e-3 * expected) << name << " row " << i;
      }
    }
    EXPECT_GT(res.rows.back().temperature - r.temperature, 50.0) << name;
  }
}

// Elastic uniaxial strain: axial stress = (K + 4G/3) strain, 1e-9 relative.
TEST(elastic_uniaxial_strain, axial_stress_is_p_wave_modulus_times_strain) {
  for (const char* name : {"al-thesis", "cu-thesis", "ti6al4v-thesis"}) {
    for (double strain : {-2e-4, 2e-4}) {
      MaterialPointRequest r = request(name, LoadingMode::uniaxial_strain, 100.0, strain, 20);
      const MaterialPointResult res = run_material_point(r);
      ASSERT_TRUE(res.converged);
      for (const MaterialPointRow& row : res.rows) {
        ASSERT_EQ(row.plastic_strain, 0.0) << name;
        const double expected =
            exact::uniaxial_strain_stress(r.material.elastic.E, r.material.elastic.nu, row.strain);
        ASSERT_NEAR(row.stress, expected, 1e-9 * std::abs(expected) + 1e-6) << name;
      }
    }
  }
}

// Johnson-Cook ductile damage in uniaxial tension (triaxiality 1/3): damage
// starts at the failure strain of eq. 2.6 and grows as eq. 2.7 to D_max.
// Damage tolerance 2e-3 absolute (one step of plastic strain is 1e-3).
TEST(jc_ductile_damage, initiates_at_failure_strain_and_grows_linearly) {
  for (double rate : {1.0, 1e3}) {
    for (double T_offset : {0.0, 300.0}) {
      MaterialPointRequest r = request("cu-thesis", LoadingMode::uniaxial_stress, rate, 2.2, 2200);
      r.switches.adiabatic_heating = false;
      r.temperature += T_offset;
      const MaterialPointResult res = run_material_point(r);
      ASSERT_TRUE(res.converged) << res.message;
      const Material& m = r.material;
      const JohnsonCookFailureParams& d = m.damage.jc;
      const double t_star = T_offset / (std::get<JohnsonCookParams>(m.strength).T_melt -
                                        std::get<JohnsonCookParams>(m.strength).T_ref);
      const double eps_f = exact::jc_failure_strain(
          d.D1, d.D2, d.D3, d.D4, d.D5, 1.0 / 3.0,
          rate / std::get<JohnsonCookParams>(m.strength).eps_dot_0, t_star);
      double first_damaged_eps = -1.0;
      for (const MaterialPointRow& row : res.rows) {
        if (row.time > 0.0) {
          ASSERT_NEAR(row.triaxiality, 1.0 / 3.0, 1e-6);
        }
        const double expected =
            exact::linear_damage(row.plastic_strain, eps_f, m.damage.eps_p_max, m.damage.D_max);
        ASSERT_NEAR(row.damage, expected, 2e-3) << "eps_p " << row.plastic_strain;
        if (first_damaged_eps < 0.0 && row.damage > 0.0) first_damaged_eps = row.plastic_strain;
      }
      EXPECT_NEAR(first_damaged_eps, eps_f, 2e-3);
      EXPECT_DOUBLE_EQ(res.rows.back().damage, m.damage.D_max);
    }
  }
}

// Shear-failure initiation (eq. 2.3-2.5) in uniaxial compression:
// theta = (k_s p + q) / tau_max = 2 (1 + k_s / 3), clamped to the bounds;
// failure strain interpolated linearly in rate between the two cubics.
// Tolerance 3e-3 in plastic strain: one step is 5e-4, and below 250 /s the
// plastic rate lags the imposed one by the elastic part (< 0.5 %).
TEST(shear_failure_damage, initiates_at_interpolated_shear_failure_strain) {
  for (double rate : {1e-3, 1.0, 100.0, 1e5}) {
    MaterialPointRequest r = request("al-thesis", LoadingMode::uniaxial_stress, rate, -2.0, 4000);
    r.switches.adiabatic_heating = false;
    const MaterialPointResult res = run_material_point(r);
    ASSERT_TRUE(res.converged) << res.message;
    const ShearFailureParams& sf = r.material.damage.shear;
    const double theta = std::clamp(2.0 * (1.0 + sf.k_s / 3.0), sf.theta_min, sf.theta_max);
    auto cubic = [theta](const double* c) {
      return c[0] * theta * theta * theta + c[1] * theta * theta + c[2] * theta + c[3];
    };
    const double w = std::clamp((rate - sf.rate_low) / (sf.rate_high - sf.rate_low), 0.0, 1.0);
    const double eps_s = cubic(sf.low) + w * (cubic(sf.high) - cubic(sf.low));
    double first = -1.0;
    for (const MaterialPointRow& row : res.rows) {
      if (row.damage > 0.0) {
        first = row.plastic_strain;
        break;
      }
    }
    EXPECT_NEAR(first, eps_s, 3e-3) << "rate " << rate;
  }
}

// Simple shear of a rate- and temperature-insensitive material: tau =
// sigma_y(eps_p) / sqrt(3) with eps_p = gamma_p / sqrt(3) while rotations are
// small (gamma <= 0.3: the Jaumann normal stresses change tau by < 0.5 %).
TEST(simple_shear, shear_stress_follows_von_mises_flow_stress) {
  MaterialPointRequest r = request("cu-thesis", LoadingMode::simple_shear, 1.0, 0.3, 3000);
  r.switches.adiabatic_heating = false;
  r.switches.damage = false;
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged);
  const exact::JcCurve c = curve_of(r.material);
  for (const MaterialPointRow& row : res.rows) {
    if (row.plastic_strain < 0.02) continue;
    const double tau =
        exact::jc_flow_stress(c, row.plastic_strain, 1.0, r.temperature) / std::sqrt(3.0);
    ASSERT_NEAR(row.stress, tau, 5e-3 * tau) << "gamma " << row.strain;
  }
}

// The Jaumann (Hughes-Winget) rotation of a stress under a constant spin is
// the rigid rotation R(theta) s R(theta)^T, theta = omega t (Rodrigues).
// Hughes-Winget is a Cayley transform whose angle per step is off by
// (omega dt)^3 / 12; over 1000 steps of 60 degrees that is ~1e-7 of |s|. (Not
// 90 degrees: a symmetric tensor turned by +90 and -90 degrees is the same.)
TEST(objective_rate, jaumann_rotation_matches_rigid_rotation) {
  Mat3 s0 = Mat3::Zero();
  s0(0, 0) = 1.0, s0(1, 1) = -0.5, s0(2, 2) = -0.5, s0(0, 1) = s0(1, 0) = 0.3;
  const double omega = 2.0;  // rad/s about z
  Mat3 W = Mat3::Zero();
  W(0, 1) = -omega, W(1, 0) = omega;  // skew(grad v) of v = omega e_z x x
  const int steps = 1000;
  const double t_end = 3.14159265358979323846 / 3.0 / omega;
  const double dt = t_end / steps;
  Mat3 s = s0;
  for (int i = 0; i < steps; ++i) s = jaumann_rotate(s, W, dt);
  const double th = omega * t_end;
  Mat3 R = Mat3::Identity();
  R(0, 0) = std::cos(th), R(0, 1) = -std::sin(th), R(1, 0) = std::sin(th), R(1, 1) = std::cos(th);
  const Mat3 expected = R * s0 * R.transpose();
  EXPECT_LT((s - expected).norm(), 1e-6 * s0.norm()) << s << "\nexpected\n" << expected;
}

// Elastic simple shear with the Jaumann rate has the closed form
// sigma_xy = G sin(gamma) (the classic hypo-elastic oscillation), which tests
// the rotation at large gamma: without it sigma_xy = G gamma. Tolerance 1e-4 G.
TEST(simple_shear, elastic_jaumann_closed_form_at_large_shear) {
  MaterialPointRequest r = request("cu-thesis", LoadingMode::simple_shear, 1.0, 2.0, 20000);
  std::get<JohnsonCookParams>(r.material.strength).A = 1e15;  // stays elastic
  r.switches.damage = false;
  const MaterialPointResult res = run_material_point(r);
  ASSERT_TRUE(res.converged);
  const double G = r.material.elastic.shear_modulus();
  for (const MaterialPointRow& row : res.rows) {
    ASSERT_NEAR(row.stress, G * std::sin(row.strain), 1e-4 * G) << "gamma " << row.strain;
  }
}

}  // namespace
}  // namespace splat
