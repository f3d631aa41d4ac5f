// heat_conduction: the finite-volume conduction between FE elements
// (solver/fe/heat_conduction.hpp) against closed forms of the heat equation
// rho c_p dT/dt = k lap T with insulated boundaries:
// - a bar along x with T = T0 + a cos(pi x / L) decays as exp(-alpha (pi/L)^2 t),
//   alpha = k / (rho c_p) (Carslaw and Jaeger 1959, 3.3);
// - an axisymmetric cylinder of radius R with T = T0 + a J0(lambda r),
//   J1(lambda R) = 0 (lambda R = 3.8317), decays as exp(-alpha lambda^2 t)
//   (Carslaw and Jaeger 1959, 7.4);
// both conserving the heat sum rho0 c_p V0 T; the stable step of an interior
// hexahedron of side h is rho c_p h^2 / (6 k); the strength of a heated point
// follows its new temperature.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/fe/heat_conduction.hpp"
#include "solver/mesh/generators.hpp"
#include "support/materials.hpp"

namespace splat {
namespace {

using test_support::jc_copper;

Material conducting_copper() {
  Material m = jc_copper();
  m.thermal.conductivity = 390.0;  // W/(m K)
  return m;
}

ModelSwitches conducting() {
  ModelSwitches sw;
  sw.heat_conduction = true;
  return sw;
}

double alpha(const Material& m) {
  return m.thermal.conductivity / (m.density * m.thermal.c_p);
}

double heat_sum(const FeBody& b) {
  double h = 0.0;
  for (std::size_t e = 0; e < b.num_elements(); ++e)
    h += b.constants.rho0 * b.material.thermal.c_p * b.volume0[e] * b.state[e].T;
  return h;
}

Vec3 centre(const FeBody& b, const NodeSet& nodes, std::size_t e) {
  Vec3 c = Vec3::Zero();
  for (int a = 0; a < b.nodes_per_element(); ++a) c += nodes.x[b.conn[e][a]];
  return c / b.nodes_per_element();
}

void set_temperature(FeBody& b, std::size_t e, double T) {
  add_heat(b.material, b.constants, b.switches, b.state[e],
           b.constants.rho0 * b.material.thermal.c_p * (T - b.state[e].T));
}

// Runs conduction to time t at half the stable step (at most 1e6 steps).
void conduct(FeBody& b, const NodeSet& nodes, double t) {
  const double dt = 0.5 * fe_conduct_heat(b, nodes, 0.0);
  const double steps = std::ceil(t / dt);
  ASSERT_LT(steps, 1e6) << "stable step " << dt << " s";
  for (int s = 0; s < static_cast<int>(steps); ++s) fe_conduct_heat(b, nodes, t / steps);
}

TEST(HeatConduction, CosineModeOfABarDecaysAtTheClosedFormRate) {
  const double L = 20e-6, h = L / 40;
  const HexMesh mesh = hex_box({0, 0, 0}, {L, h, h}, 40, 1, 1, Grading{});
  NodeSet nodes;
  FeBody b = make_fe_body("bar", mesh, conducting_copper(), conducting(), FeSettings{},
                          Vec3::Zero(), 300.0, 1, nodes);
  const double a = 100.0;
  for (std::size_t e = 0; e < b.num_elements(); ++e)
    set_temperature(b, e, 300.0 + a * std::cos(std::numbers::pi * centre(b, nodes, e)[0] / L));
  const double heat0 = heat_sum(b);
  const double k = std::numbers::pi / L;
  const double t = 0.5 / (alpha(b.material) * k * k);  // amplitude to e^-0.5
  conduct(b, nodes, t);
  const double expected = std::exp(-alpha(b.material) * k * k * t);
  for (std::size_t e = 0; e < b.num_elements(); ++e) {
    const double c = std::cos(k * centre(b, nodes, e)[0]);
    // Second-order scheme: (k h)^2 / 12 = 5e-4 of the rate, plus the
    // first-order time error (dt / t ~ 1e-3); 1 % of the amplitude.
    EXPECT_NEAR(b.state[e].T - 300.0, a * expected * c, 0.01 * a) << "element " << e;
  }
  EXPECT_NEAR(heat_sum(b), heat0, 1e-12 * heat0);
}

TEST(HeatConduction, BesselModeOfAnAxisymmetricCylinderDecaysAtTheClosedFormRate) {
  const double R = 10e-6;
  const AxisymMesh mesh = axisym_rectangle(R, 0.0, R / 40, 40, 1, Grading{});
  NodeSet nodes;
  FeBody b = make_fe_body("disc", mesh, conducting_copper(), conducting(), FeSettings{},
                          Vec3::Zero(), 300.0, 1, nodes);
  const double lambda = 3.8317059702075125 / R;  // first zero of J1
  const double a = 100.0;
  for (std::size_t e = 0; e < b.num_elements(); ++e)
    set_temperature(b, e, 300.0 + a * std::cyl_bessel_j(0.0, lambda * centre(b, nodes, e)[0]));
  const double heat0 = heat_sum(b);
  const double t = 0.5 / (alpha(b.material) * lambda * lambda);
  conduct(b, nodes, t);
  const double expected = std::exp(-alpha(b.material) * lambda * lambda * t);
  for (std::size_t e = 0; e < b.num_elements(); ++e) {
    const double J0 = std::cyl_bessel_j(0.0, lambda * centre(b, nodes, e)[0]);
    EXPECT_NEAR(b.state[e].T - 300.0, a * expected * J0, 0.01 * a) << "element " << e;
  }
  EXPECT_NEAR(heat_sum(b), heat0, 1e-12 * heat0);
}

TEST(HeatConduction, StableStepOfAnInteriorHexahedronIsRhoCpHSquaredOverSixK) {
  const double h = 1e-6;
  const HexMesh mesh = hex_box({0, 0, 0}, {3 * h, 3 * h, 3 * h}, 3, 3, 3, Grading{});
  NodeSet nodes;
  FeBody b = make_fe_body("cube", mesh, conducting_copper(), conducting(), FeSettings{},
                          Vec3::Zero(), 300.0, 1, nodes);
  const Material& m = b.material;
  const double expected = m.density * m.thermal.c_p * h * h / (6.0 * m.thermal.conductivity);
  EXPECT_NEAR(fe_conduct_heat(b, nodes, 0.0), expected, 1e-9 * expected);
}

TEST(HeatConduction, AMaterialWithoutConductivityOrWithTheSwitchOffConductsNothing) {
  const HexMesh mesh = hex_box({0, 0, 0}, {2e-6, 1e-6, 1e-6}, 2, 1, 1, Grading{});
  NodeSet nodes;
  FeBody plain = make_fe_body("plain", mesh, jc_copper(), conducting(), FeSettings{}, Vec3::Zero(),
                              300.0, 1, nodes);
  EXPECT_FALSE(conducts_heat(plain));
  EXPECT_TRUE(plain.heat_faces.empty());
  const ModelSwitches off;  // heat_conduction is off by default
  FeBody switched = make_fe_body("off", mesh, conducting_copper(), off, FeSettings{}, Vec3::Zero(),
                                 300.0, 1, nodes);
  set_temperature(switched, 0, 500.0);
  EXPECT_TRUE(std::isinf(fe_conduct_heat(switched, nodes, 1e-9)));
  EXPECT_EQ(switched.state[0].T, 500.0);
  EXPECT_EQ(switched.state[1].T, 300.0);
}

TEST(HeatConduction, AddedHeatSoftensThePointAsItsNewTemperatureSays) {
  const Material m = jc_copper();
  const MaterialConstants mc = derive_constants(m);
  const ModelSwitches sw;
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  const double e0 = st.e;
  add_heat(m, mc, sw, st, mc.rho0 * m.thermal.c_p * 400.0);
  const PointState hot = initial_point_state(m, sw, 700.0, 0.0);
  EXPECT_NEAR(st.T, 700.0, 1e-9);
  EXPECT_NEAR(st.e - e0, mc.rho0 * m.thermal.c_p * 400.0, 1e-6);
  EXPECT_NEAR(st.sigma_y_static, hot.sigma_y_static, 1e-9 * hot.sigma_y_static);
  EXPECT_NEAR(st.strength_scale, hot.strength_scale, 1e-12);
}

}  // namespace
}  // namespace splat
