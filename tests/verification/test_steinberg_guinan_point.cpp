// Uniaxial strain with the Steinberg-Guinan law: `splat mat-point`'s driver
// compresses (and, separately, stretches) a point of each Steinberg-Guinan
// library file laterally confined at 1e5 /s with adiabatic heating, so that
// pressure, compression and temperature all move. The von Mises stress of
// each plastic step, 1.5 |sigma_xx + P| (the deviator of uniaxial strain is
// s_xx (1, -1/2, -1/2)), is the closed form
//   Y(eps_p) (1 + A P / eta^(1/3) - B (T - T_ref)),
// Y(eps_p) = min(Y0 (1 + beta (eps_i + eps_p))^n, Y_max),
// (tests/exact/steinberg_guinan_closed_form.hpp, with the source's numbers
// of tests/exact/sg_library_sources.hpp) at the step's end plastic strain
// and the P, eta = exp(-strain) and T at its start (the law sees the state
// at the start of the step, as with T), within 1e-9 (the return's tolerance
// is 1e-11 of the trial stress). Against the state at the end of the step
// the difference is what one step moves P and T: below 1e-3 with 3000
// steps. Without the pressure term the compressed zinc is 36 % off; without
// the refresh of the cached yield stress after elastic steps
// (point_update.cpp) compressed zinc and AZ31B are 0.6 and 1.4 % off and
// their returns fail to converge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "exact/sg_library_sources.hpp"
#include "exact/steinberg_guinan_closed_form.hpp"
#include "solver/input/material_io.hpp"
#include "solver/material/material_point_driver.hpp"
#include "solver/material/steinberg_guinan.hpp"

namespace splat {
namespace {

struct Deviation {
  double at_start = 0.0;  // worst relative deviation, state at the start of the step
  double at_end = 0.0;    // worst relative deviation, state at the end of the step
  double factor = 1.0;    // 1 + A P / eta^(1/3) at the last row
  double heating = 0.0;   // temperature rise at the last row, K
};

Deviation run_uniaxial_strain(const exact::SgSourceSet& s, double max_strain) {
  MaterialPointRequest r;
  r.material = load_material(s.material);
  r.mode = LoadingMode::uniaxial_strain;
  r.strain_rate = 1e5;
  r.max_strain = max_strain;
  r.steps = 3000;
  r.temperature = s.curve.T_ref;
  r.switches.damage = false;
  const MaterialPointResult res = run_material_point(r);
  EXPECT_TRUE(res.converged) << s.material << ": " << res.message;
  Deviation d;
  int plastic_rows = 0;
  for (std::size_t k = 1; k < res.rows.size(); ++k) {
    const MaterialPointRow& before = res.rows[k - 1];
    const MaterialPointRow& row = res.rows[k];
    if (!(row.plastic_strain > before.plastic_strain)) continue;
    ++plastic_rows;
    const double q = 1.5 * std::abs(row.stress + row.pressure);
    const double at_start =
        exact::sg_flow_stress(s.curve, row.plastic_strain, 0.0, before.temperature, before.pressure,
                              std::exp(-before.strain));
    const double at_end = exact::sg_flow_stress(s.curve, row.plastic_strain, 0.0, row.temperature,
                                                row.pressure, std::exp(-row.strain));
    d.at_start = std::max(d.at_start, std::abs(q - at_start) / at_start);
    d.at_end = std::max(d.at_end, std::abs(q - at_end) / at_end);
  }
  EXPECT_GT(plastic_rows, 1000) << s.material;
  const MaterialPointRow& last = res.rows.back();
  d.factor = 1.0 + s.curve.A * last.pressure / std::cbrt(std::exp(-last.strain));
  d.heating = last.temperature - s.curve.T_ref;
  return d;
}

TEST(uniaxial_strain_steinberg_guinan, flow_stress_carries_the_pressure_term) {
  for (const exact::SgSourceSet& s : exact::sg_library_sources) {
    for (double max_strain : {-0.15, 0.05}) {
      const Deviation d = run_uniaxial_strain(s, max_strain);
      std::printf(
          "%s, uniaxial strain to %+.2f: 1 + A P / eta^(1/3) %.3f, heating %.1f K; worst "
          "deviation from the closed form at the step's start state %.1e, end state %.1e\n",
          s.material, max_strain, d.factor, d.heating, d.at_start, d.at_end);
      EXPECT_LT(d.at_start, 1e-9) << s.material << " to " << max_strain;
      EXPECT_LT(d.at_end, 1e-3) << s.material << " to " << max_strain;
      // The terms under test are not small: compression raises the strength
      // by a quarter or more, tension lowers it, the heating moves it.
      if (max_strain < 0.0) {
        EXPECT_GT(d.factor, 1.25) << s.material;
      } else {
        EXPECT_LT(d.factor, 0.95) << s.material;
      }
      EXPECT_GT(d.heating, 0.1) << s.material;
    }
  }
}

// However far stretched, the strength is not negative: G(P, T) / G0 is
// clamped at 0 (zinc at P = -50 GPa, eta = 0.5: 1 + A P / eta^(1/3) = -2.75).
TEST(uniaxial_strain_steinberg_guinan, strength_is_never_negative) {
  const exact::SgCurve& c = exact::sg_library_sources[0].curve;
  const SteinbergGuinanParams zinc{.Y0 = c.Y0,
                                   .Y_max = c.Y_max,
                                   .beta = c.beta,
                                   .n = c.n,
                                   .eps_i = c.eps_i,
                                   .A = c.A,
                                   .B = c.B,
                                   .T_ref = c.T_ref,
                                   .T_melt = c.T_melt};
  ASSERT_LT(1.0 + c.A * -50e9 / std::cbrt(0.5), 0.0);
  const FlowStress f = flow_stress(zinc, ModelSwitches{}, 0.1, 1e5, 300.0, {-50e9, 0.5});
  EXPECT_EQ(f.value, 0.0);
  EXPECT_EQ(f.d_eps_p, 0.0);
  EXPECT_EQ(exact::sg_flow_stress(c, 0.1, 1e5, 300.0, -50e9, 0.5), 0.0);
}

}  // namespace
}  // namespace splat
