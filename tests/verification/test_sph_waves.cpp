// elastic_wave_speed_sph_column: a longitudinal wave in an SPH column held in
// uniaxial strain, against the closed-form P-wave speed and front stress.
//
// A column of elastic aluminium, cubic lattice, 3 x 3 particles across and
// 100 along z. Every particle's lateral velocity is held at zero (uniaxial
// strain; the corrected gradient makes the lateral free surfaces exact for
// this laterally uniform field), and the first two layers at z_min move at
// v0 along +z from t = 0:
//
//    v0 -> |##|..........................................| free end
//          z_min     station 1        station 2
//
// The arrival time of the front at a station is when the station layer's
// mean axial velocity first reaches v0 / 2; the measured speed is the
// station distance over the arrival-time difference (the loading start and
// the front's rise time cancel). Compared with c_L = sqrt(E (1 - nu) /
// ((1 + nu)(1 - 2 nu) rho)) to 2 %, and the stress behind the front with
// -rho c_L v0 to 3 %.
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

struct WaveResult {
  double speed = 0.0;         // m/s
  double front_stress = 0.0;  // sigma_zz behind the front, Pa
};

WaveResult column_wave(const SphSettings& settings, SphKernel kernel) {
  const double d = 1e-4;  // spacing, m
  ParticleSpec s;
  s.shape = ParticleShape::box;
  s.lattice = Lattice::cubic;
  s.lo = Vec3(0, 0, 0);
  s.hi = Vec3(3 * d, 3 * d, 100 * d);
  s.spacing = d;
  s.boundary_layers = 2;
  const ParticleCloud cloud = generate_particles(s);
  SphDriver drv;
  ModelSwitches sw;
  sw.damage = false;
  sw.adiabatic_heating = false;
  SphSettings st = settings;
  st.kernel = kernel;
  drv.bodies.push_back(make_sph_body("column", cloud, elastic_aluminium(), sw, st, {}, Vec3::Zero(),
                                     300.0, 1, drv.nodes));
  const double v0 = 1.0;  // m/s
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const bool driven = (cloud.boundary[i] & boundary_z_min) != 0;
    drv.prescribe(i, driven ? 0b111 : 0b011, Vec3(0, 0, driven ? v0 : 0.0));
  }
  drv.stability = 0.5;
  EXPECT_EQ(drv.start(), SphOutcome::running);

  const double z1 = 30.5 * d, z2 = 80.5 * d;  // station layers (particle centres)
  const auto layer_velocity = [&](double z) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (std::abs(cloud.x[i].z() - z) < 0.1 * d) {
        sum += drv.nodes.v[i].z();
        ++count;
      }
    }
    return sum / count;
  };
  const double c = exact::longitudinal_wave_speed(70e9, 0.3, 2700.0);
  double t1 = -1.0, t2 = -1.0, prev1 = 0.0, prev2 = 0.0, t_prev = 0.0;
  WaveResult out;
  while (t2 < 0.0 && drv.time() < 2.0 * 100 * d / c) {
    if (drv.step() != SphOutcome::running) {
      ADD_FAILURE() << drv.reason();
      return out;
    }
    const double u1 = layer_velocity(z1), u2 = layer_velocity(z2);
    const double t = drv.time();
    // Linear interpolation of the crossing of v0 / 2.
    if (t1 < 0.0 && u1 >= 0.5 * v0) t1 = t_prev + (t - t_prev) * (0.5 * v0 - prev1) / (u1 - prev1);
    if (t2 < 0.0 && u2 >= 0.5 * v0) t2 = t_prev + (t - t_prev) * (0.5 * v0 - prev2) / (u2 - prev2);
    prev1 = u1, prev2 = u2, t_prev = t;
    if (t1 > 0.0 && out.front_stress == 0.0 && t > t1 + 20 * d / c) {
      // Mean sigma_zz over the layer at station 1, well behind the front.
      double sum = 0.0;
      int count = 0;
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (std::abs(cloud.x[i].z() - z1) < 0.1 * d) {
          sum += drv.bodies[0].state[i].cauchy()(2, 2);
          ++count;
        }
      }
      out.front_stress = sum / count;
    }
  }
  out.speed = (z2 - z1) / (t2 - t1);
  return out;
}

TEST(SphWaves, ElasticWaveSpeedInAColumn) {
  const double c = exact::longitudinal_wave_speed(70e9, 0.3, 2700.0);
  const double sigma = exact::wave_front_stress(2700.0, c, 1.0);
  for (SphKernel kernel : {SphKernel::cubic_spline, SphKernel::wendland_c2}) {
    const WaveResult r = column_wave(SphSettings{}, kernel);
    std::printf(
        "kernel %d: c measured %.1f m/s, c_L %.1f m/s (%.2f %%); front stress %.4g Pa, "
        "-rho c_L v0 %.4g Pa (%.2f %%)\n",
        static_cast<int>(kernel), r.speed, c, 100.0 * (r.speed / c - 1.0), r.front_stress, sigma,
        100.0 * (r.front_stress / sigma - 1.0));
    EXPECT_NEAR(r.speed / c, 1.0, 0.02);
    EXPECT_NEAR(r.front_stress / sigma, 1.0, 0.03);
  }
}

// elastic_bar_wave_speed_sph: the same column with free lateral surfaces
// (3 x 3 particles across, 200 long) driven by a velocity ramp over
// t_r = 20 w / c_bar (w the width), so the pulse is long against the width
// and the Pochhammer dispersion correction, about nu^2 pi^2 (r / lambda)^2
// < 0.1 %, is negligible: the half-amplitude point must travel at the bar
// speed c_bar = sqrt(E / rho) to 3 %. (At uniaxial strain it would be
// c_L, 16 % faster; at 3 particles across the lateral free surfaces are as
// coarse as they get.)
TEST(SphWaves, ElasticBarWaveSpeed) {
  const double d = 1e-4;
  ParticleSpec s;
  s.shape = ParticleShape::box;
  s.lattice = Lattice::cubic;
  s.hi = Vec3(3 * d, 3 * d, 200 * d);
  s.spacing = d;
  s.boundary_layers = 2;
  const ParticleCloud cloud = generate_particles(s);
  SphDriver drv;
  ModelSwitches sw;
  sw.damage = false;
  sw.adiabatic_heating = false;
  drv.bodies.push_back(make_sph_body("bar", cloud, elastic_aluminium(), sw, SphSettings{}, {},
                                     Vec3::Zero(), 300.0, 1, drv.nodes));
  const double c_bar = exact::bar_wave_speed(70e9, 2700.0);
  const double v0 = 1.0, t_r = 20 * 3 * d / c_bar;
  const auto drive = [&](double t) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (cloud.boundary[i] & boundary_z_min) {
        drv.prescribe(i, 0b100, Vec3(0, 0, v0 * std::min(t / t_r, 1.0)));
      }
    }
  };
  drive(0.0);
  ASSERT_EQ(drv.start(), SphOutcome::running);
  const double z1 = 60.5 * d, z2 = 160.5 * d;
  const auto layer_velocity = [&](double z) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (std::abs(cloud.x[i].z() - z) < 0.1 * d) sum += drv.nodes.v[i].z(), ++count;
    }
    return sum / count;
  };
  double t1 = -1.0, t2 = -1.0, prev1 = 0.0, prev2 = 0.0, t_prev = 0.0;
  while (t2 < 0.0 && drv.time() < 2.0 * 200 * d / c_bar + t_r) {
    drive(drv.time() + drv.dt());
    ASSERT_EQ(drv.step(), SphOutcome::running) << drv.reason();
    const double u1 = layer_velocity(z1), u2 = layer_velocity(z2), t = drv.time();
    if (t1 < 0.0 && u1 >= 0.5 * v0) t1 = t_prev + (t - t_prev) * (0.5 * v0 - prev1) / (u1 - prev1);
    if (t2 < 0.0 && u2 >= 0.5 * v0) t2 = t_prev + (t - t_prev) * (0.5 * v0 - prev2) / (u2 - prev2);
    prev1 = u1, prev2 = u2, t_prev = t;
  }
  ASSERT_GT(t2, 0.0);
  const double c = (z2 - z1) / (t2 - t1);
  std::printf("bar: c measured %.1f m/s, c_bar %.1f m/s (%.2f %%)\n", c, c_bar,
              100.0 * (c / c_bar - 1.0));
  EXPECT_NEAR(c / c_bar, 1.0, 0.03);
}

}  // namespace
}  // namespace splat
