// max_shear_stress (the shear-failure criterion's tau_max, point_update.cpp)
// against the principal stresses from Eigen's iterative symmetric eigensolver
// (QL with implicit shifts, accurate to rounding relative to the largest
// eigenvalue): random stresses, the states where two principal stresses
// coincide (uniaxial, equibiaxial), pure shear, pure pressure and zero.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "solver/material/damage.hpp"

namespace splat {
namespace {

double reference_tau(const Mat3& sigma) {
  Eigen::SelfAdjointEigenSolver<Mat3> es(sigma, Eigen::EigenvaluesOnly);
  return 0.5 * (es.eigenvalues()(2) - es.eigenvalues()(0));
}

Mat3 rotated(const Vec3& principal, const Mat3& Q) {
  return Q * principal.asDiagonal() * Q.transpose();
}

Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

TEST(max_shear_stress, matches_the_eigenvalues_of_random_stresses) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    Mat3 s;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) s(i, j) = s(j, i) = 1e9 * u(rng);
    s.diagonal().array() += 3e9 * u(rng);  // a pressure up to 3 GPa
    const double ref = reference_tau(s);
    worst = std::max(worst, std::abs(max_shear_stress(s) - ref) / ref);
  }
  // Generic stresses: well separated principal values.
  EXPECT_LT(worst, 1e-11);
}

TEST(max_shear_stress, exact_on_the_closed_forms) {
  std::mt19937_64 rng(11);
  const double sig = 250e6, p = 1.7e9;
  for (int k = 0; k < 200; ++k) {
    const Mat3 Q = random_rotation(rng);
    // Uniaxial (r = 1) and equibiaxial (r = -1) on a pressure: tau = sig / 2.
    EXPECT_NEAR(max_shear_stress(rotated(Vec3(sig - p, -p, -p), Q)), 0.5 * sig, 1e-7 * sig);
    EXPECT_NEAR(max_shear_stress(rotated(Vec3(-p, -p, -sig - p), Q)), 0.5 * sig, 1e-7 * sig);
    // Pure shear (r = 0): tau = sig.
    EXPECT_NEAR(max_shear_stress(rotated(Vec3(sig, 0.0, -sig), Q)), sig, 1e-12 * sig);
    // Close to a double eigenvalue: gap 1e-4 of the stress.
    const Vec3 near(sig, sig * (1.0 - 1e-4), -sig);
    EXPECT_NEAR(max_shear_stress(rotated(near, Q)), sig, 1e-9 * sig);
  }
  EXPECT_EQ(max_shear_stress(Mat3::Zero()), 0.0);
  EXPECT_EQ(max_shear_stress(-p * Mat3::Identity()), 0.0);
}

}  // namespace
}  // namespace splat
