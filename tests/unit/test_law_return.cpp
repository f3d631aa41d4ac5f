// The general radial return of strength_model.hpp (law_return) with the
// Zerilli-Armstrong and Preston-Tonks-Wallace laws of copper and the
// Steinberg-Guinan law of zinc under 2 GPa and in tension: it converges,
// and the returned stress lies on the flow surface, at every plastic strain,
// rate and temperature an impact visits, including eps_p = 0 (unbounded
// slope for Zerilli-Armstrong), the overdriven-shock branch of
// Preston-Tonks-Wallace and the melt (no strength).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/material/strength_model.hpp"

namespace splat {
namespace {

ZerilliArmstrongParams za_copper() {
  return {.C0 = 46.5e6,
          .C2 = 890e6,
          .C3 = 0.0028,
          .C4 = 0.000115,
          .eps_dot_0 = 1.0,
          .T_ref = 300.0,
          .T_melt = 1356.0};
}

PrestonTonksWallaceParams ptw_copper() {
  return {.theta = 0.025,
          .p = 2.0,
          .s0 = 0.0085,
          .s_inf = 0.00055,
          .kappa = 0.11,
          .gamma = 1e-5,
          .y0 = 0.0001,
          .y_inf = 0.0001,
          .y1 = 0.094,
          .y2 = 0.575,
          .beta = 0.25,
          .G = 45.78e9,
          .rho = 8937.5,
          .M = 0.063546,
          .eps_dot_0 = 1.0,
          .T_ref = 300.0,
          .T_melt = 1356.0};
}

template <class Law>
void expect_returns_onto_the_flow_surface(const Law& law, const PressureState& ps = {}) {
  const ModelSwitches sw;
  const double G = 46e9;  // Pa
  for (double eps_p : {0.0, 1e-6, 0.01, 1.0, 5.0}) {
    for (double rate : {1e-3, 1.0, 1e4, 1e7, 1e9}) {
      for (double T : {300.0, 900.0, 1355.0, 1400.0}) {
        const double dt = 1e-9;
        // A trial stress 1.5 times the flow stress at the imposed rate, plus
        // what the elastic predictor of one step adds.
        const double sigma = flow_stress(law, sw, eps_p, rate, T, ps).value;
        const double q_trial = 1.5 * sigma + 3.0 * G * rate * dt + 1e6;
        const LawReturn r = law_return(law, sw, q_trial, G, 0.95, eps_p, dt, T, ps);
        SCOPED_TRACE(::testing::Message() << "eps_p " << eps_p << " rate " << rate << " T " << T);
        ASSERT_TRUE(r.converged);
        EXPECT_LT(r.iterations, 60);
        const double dp = r.delta_eps_p;
        ASSERT_GE(dp, 0.0);
        const double on_surface = 0.95 * flow_stress(law, sw, eps_p + dp, dp / dt, T, ps).value;
        EXPECT_NEAR(q_trial - 3.0 * G * dp, on_surface, 1e-9 * q_trial);
      }
    }
  }
}

TEST(law_return, lands_on_the_flow_surface_zerilli_armstrong) {
  expect_returns_onto_the_flow_surface(za_copper());
}

TEST(law_return, lands_on_the_flow_surface_preston_tonks_wallace) {
  expect_returns_onto_the_flow_surface(ptw_copper());
}

// Steinberg (1996), zinc (materials/zn-sg.json), compressed (P 2 GPa,
// eta 1.03) and stretched (P -2 GPa, eta 0.97).
TEST(law_return, lands_on_the_flow_surface_steinberg_guinan) {
  const SteinbergGuinanParams zinc{.Y0 = 0.15e9,
                                   .Y_max = 0.92e9,
                                   .beta = 100.0,
                                   .n = 0.2,
                                   .eps_i = 0.0,
                                   .A = 5.95e-11,
                                   .B = 7.60e-4,
                                   .T_ref = 300.0,
                                   .T_melt = 900.0};
  expect_returns_onto_the_flow_surface(zinc, {2e9, 1.03});
  expect_returns_onto_the_flow_surface(zinc, {-2e9, 0.97});
}

}  // namespace
}  // namespace splat
