// SPH kernels and particle generation: normalisation, derivatives, lattice
// volumes and spacings.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/mesh/mesh.hpp"
#include "solver/sph/sph_kernel.hpp"
#include "solver/sph/sph_particles.hpp"

namespace splat {
namespace {

// int_0^2h 4 pi r^2 W dr by composite Simpson on [0, h] and [h, 2h] (the
// pieces of both kernels are polynomials of degree <= 5 in r: Simpson with
// 2000 panels is exact to round-off well below the tolerance).
double integral(SphKernel type, double h) {
  const int n = 2000;
  const double step = h / n;
  double sum = 0.0;
  for (int piece = 0; piece < 2; ++piece) {
    const double a = piece * h;
    for (int k = 0; k <= n; ++k) {
      const double r = a + k * step;
      const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      sum += w * 4.0 * std::numbers::pi * r * r * kernel(type, r, h).w;
    }
  }
  return sum * step / 3.0;
}

TEST(SphKernel, NormalisedToOneIn3D) {
  for (SphKernel type : {SphKernel::cubic_spline, SphKernel::wendland_c2}) {
    for (double h : {1e-6, 1.25e-6, 3.0}) {
      EXPECT_NEAR(integral(type, h), 1.0, 1e-10) << static_cast<int>(type) << " h " << h;
    }
  }
}

TEST(SphKernel, DerivativeMatchesFiniteDifference) {
  const double h = 2e-6;
  for (SphKernel type : {SphKernel::cubic_spline, SphKernel::wendland_c2}) {
    for (double q = 0.05; q < 2.0; q += 0.1) {
      const double r = q * h, e = 1e-6 * h;
      const double fd = (kernel(type, r + e, h).w - kernel(type, r - e, h).w) / (2 * e);
      const KernelValue k = kernel(type, r, h);
      EXPECT_NEAR(k.dw_dr, fd, 1e-6 * std::abs(kernel(type, 0.0, h).w) / h) << q;
      EXPECT_LE(k.dw_dr, 0.0);
    }
    EXPECT_EQ(kernel(type, 2.0 * h, h).w, 0.0);
    EXPECT_EQ(kernel(type, 2.5 * h, h).dw_dr, 0.0);
  }
}

TEST(SphParticles, CubicBoxFillsTheBoxExactly) {
  ParticleSpec s;
  s.shape = ParticleShape::box;
  s.lattice = Lattice::cubic;
  s.lo = Vec3(0, 0, 0);
  s.hi = Vec3(1e-3, 2e-3, 0.55e-3);
  s.spacing = 1e-4;
  s.boundary_layers = 2;
  const ParticleCloud c = generate_particles(s);
  EXPECT_EQ(c.size(), 10u * 20u * 6u);  // round(5.5) = 6 layers along z
  EXPECT_NEAR(c.volume_error, 0.0, 1e-12);
  std::size_t on_x_min = 0;
  for (std::size_t i = 0; i < c.size(); ++i) on_x_min += (c.boundary[i] & boundary_x_min) ? 1 : 0;
  EXPECT_EQ(on_x_min, 2u * 20u * 6u);
}

// Nearest-neighbour distance of the HCP lattice is the spacing, each interior
// point has 12 nearest neighbours, and a sphere's lattice volume approaches
// the exact one.
TEST(SphParticles, HcpSphereHasTwelveNearestNeighboursAndItsVolume) {
  ParticleSpec s;
  s.shape = ParticleShape::sphere;
  s.radius = 12.5e-6;
  s.centre = Vec3(0, 0, 20e-6);
  s.spacing = 1.25e-6;
  const ParticleCloud c = generate_particles(s);
  EXPECT_NEAR(c.volume_error, 0.0, 0.03);
  const Vec3 centre = s.centre;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if ((c.x[i] - centre).norm() > 0.5 * s.radius) continue;
    int near = 0;
    double d_min = 1.0;
    for (std::size_t j = 0; j < c.size(); ++j) {
      if (i == j) continue;
      const double d = (c.x[i] - c.x[j]).norm();
      d_min = std::min(d_min, d);
      if (d < 1.01 * s.spacing) ++near;
    }
    EXPECT_NEAR(d_min, s.spacing, 1e-12);
    EXPECT_EQ(near, 12);
  }
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double r = (c.x[i] - centre).norm();
    EXPECT_LE(r, s.radius);
    EXPECT_EQ((c.boundary[i] & boundary_curved) != 0, s.radius - r < 3 * s.spacing);
  }
}

TEST(SphParticles, QuarterCylinderStaysInItsSectorAndJitterIsReproducible) {
  ParticleSpec s;
  s.shape = ParticleShape::cylinder;
  s.lattice = Lattice::cubic;
  s.radius = 1e-3;
  s.z_min = -1e-3;
  s.z_max = 0.0;
  s.sector = ParticleSector::quarter;
  s.spacing = 1e-4;
  const ParticleCloud c = generate_particles(s);
  EXPECT_NEAR(c.volume_error, 0.0, 0.05);
  for (const Vec3& p : c.x) {
    EXPECT_GT(p.x(), 0.0);
    EXPECT_GT(p.y(), 0.0);
  }
  s.jitter = 0.1;
  const ParticleCloud a = generate_particles(s), b = generate_particles(s);
  ASSERT_EQ(a.size(), c.size());
  double moved = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.x[i], b.x[i]);
    moved = std::max(moved, (a.x[i] - c.x[i]).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(moved, 0.05 * s.spacing);
  EXPECT_LE(moved, 0.1 * s.spacing);
}

TEST(SphParticles, RejectsBadInput) {
  ParticleSpec s;
  s.radius = 1.0;
  EXPECT_THROW(generate_particles(s), std::invalid_argument);  // no spacing
  s.spacing = 0.1;
  s.jitter = 0.7;
  EXPECT_THROW(generate_particles(s), std::invalid_argument);
}

}  // namespace
}  // namespace splat
