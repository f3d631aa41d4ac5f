// Boundary conditions of SPH bodies against independent references.
//
// quarter_ball_mirrors_full_ball: a breathing and shearing elastic ball on a
// cubic lattice centred so that x = 0 and y = 0 are mirror planes of the
// particles. The quarter x, y > 0 with mirrored ghosts on both planes must
// follow the full ball's motion (the full ball is the independent
// computation; viscosity and hourglass control on): same positions to 1e-9 of
// the spacing after 300 steps, for an initial velocity field that is itself
// mirror-symmetric.
//
// absorbing_end_of_a_column: the uniaxial-strain column of test_sph_waves,
// driven at v0 at z_min. At a free end the wave reflects as tension and the
// particle velocity behind the reflection doubles (2 v0, the closed form of a
// free-end reflection); with an absorbing layer (impedance rho c_L A v_n,
// A_i = V_i / layer thickness) the velocity must stay at v0: after the
// reflection time the middle of the column stays within 10 % of v0, while
// the free end gives > 1.8 v0 (checked too, so the test sees the difference).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "exact/elastic_waves.hpp"
#include "solver/mesh/mesh.hpp"
#include "solver/sph/sph_driver.hpp"

namespace splat {
namespace {

Material elastic_aluminium() {
  Material m;
  m.name = "elastic-al";
  m.density = 2700.0;
  m.elastic = {70e9, 0.3};
  m.strength = JohnsonCookParams{.A = 1e30, .T_melt = 900.0};
  m.thermal.c_p = 900.0;
  return m;
}

ModelSwitches elastic_switches() {
  ModelSwitches sw;
  sw.damage = false;
  sw.adiabatic_heating = false;
  return sw;
}

Vec3 initial_velocity(const Vec3& r, double R) {
  // Symmetric under x -> -x and y -> -y: breathing plus a pure shear in x-z.
  return (30.0 / R) * r + (20.0 / R) * Vec3(r.x(), -r.y(), 0.0) +
         (10.0 / R) * Vec3(0.0, 0.0, r.z() * r.z() / R);
}

TEST(SphBoundaries, QuarterBallWithMirroredGhostsFollowsTheFullBall) {
  const double d = 1e-4, R = 5 * d;
  ParticleSpec s;
  s.shape = ParticleShape::sphere;
  s.lattice = Lattice::cubic;
  s.radius = R;
  s.spacing = d;
  const ParticleCloud full = generate_particles(s);
  s.sector = ParticleSector::quarter;
  const ParticleCloud quarter = generate_particles(s);
  ASSERT_EQ(4 * quarter.size(), full.size());

  const auto run = [&](const ParticleCloud& c, const SymmetryPlanes& planes) {
    SphDriver drv;
    drv.bodies.push_back(make_sph_body("ball", c, elastic_aluminium(), elastic_switches(),
                                       SphSettings{}, planes, Vec3::Zero(), 300.0, 1, drv.nodes));
    for (std::size_t i = 0; i < c.size(); ++i) drv.nodes.v[i] = initial_velocity(c.x[i], R);
    drv.fixed_dt = 0.2 * d / 6000.0;
    EXPECT_EQ(drv.start(), SphOutcome::running);
    for (int k = 0; k < 300; ++k) EXPECT_EQ(drv.step(), SphOutcome::running);
    return drv.nodes.x;
  };
  const std::vector<Vec3> xf = run(full, {});
  const std::vector<Vec3> xq = run(quarter, {{0, 0.0}, {1, 0.0}});
  double worst = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < quarter.size(); ++i) {
    // The same particle in the full ball: the one starting at the same place.
    std::size_t match = full.size();
    for (std::size_t j = 0; j < full.size(); ++j) {
      if ((full.x[j] - quarter.x[i]).norm() < 1e-3 * d) match = j;
    }
    ASSERT_LT(match, full.size());
    worst = std::max(worst, (xq[i] - xf[match]).norm());
    moved = std::max(moved, (xq[i] - quarter.x[i]).norm());
  }
  std::printf("quarter vs full ball: max position difference %.2e d (max displacement %.2e d)\n",
              worst / d, moved / d);
  EXPECT_GT(moved, 1e-3 * d);
  EXPECT_LT(worst, 1e-9 * d);
}

// Peak axial velocity in the middle of the column after the reflection from
// z_max has passed it, in units of v0.
double column_reflection(bool absorbing) {
  const double d = 1e-4;
  ParticleSpec s;
  s.shape = ParticleShape::box;
  s.lattice = Lattice::cubic;
  s.hi = Vec3(3 * d, 3 * d, 80 * d);
  s.spacing = d;
  s.boundary_layers = 2;
  const ParticleCloud cloud = generate_particles(s);
  SphDriver drv;
  drv.bodies.push_back(make_sph_body("column", cloud, elastic_aluminium(), elastic_switches(),
                                     SphSettings{}, {}, Vec3::Zero(), 300.0, 1, drv.nodes));
  const double v0 = 1.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const bool driven = (cloud.boundary[i] & boundary_z_min) != 0;
    drv.prescribe(i, driven ? 0b111 : 0b011, Vec3(0, 0, driven ? v0 : 0.0));
  }
  if (absorbing) {
    drv.absorbing.push_back(
        make_sph_absorbing(drv.bodies[0], drv.nodes, boundary_z_max, cloud.layer_thickness));
  }
  EXPECT_EQ(drv.start(), SphOutcome::running);
  const double c = exact::longitudinal_wave_speed(70e9, 0.3, 2700.0);
  const double L = 80 * d, z_mid = 40.5 * d;
  // The reflection reaches the middle at 1.5 L / c; watch until 1.9 L / c.
  double peak = 0.0;
  while (drv.time() < 1.9 * L / c) {
    EXPECT_EQ(drv.step(), SphOutcome::running);
    if (drv.time() < 1.6 * L / c) continue;
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (std::abs(cloud.x[i].z() - z_mid) < 0.1 * d) sum += drv.nodes.v[i].z(), ++count;
    }
    peak = std::max(peak, sum / count / v0);
  }
  return peak;
}

TEST(SphBoundaries, AbsorbingEndOfAColumn) {
  const double free_end = column_reflection(false);
  const double absorbed = column_reflection(true);
  std::printf("velocity behind the reflection: free end %.3f v0, absorbing end %.3f v0\n", free_end,
              absorbed);
  EXPECT_GT(free_end, 1.8);
  EXPECT_NEAR(absorbed, 1.0, 0.1);
}

}  // namespace
}  // namespace splat
