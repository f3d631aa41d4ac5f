#include "solver/fe/quad4_axisym.hpp"

#include <algorithm>

namespace splat {

Quad4Gradient quad4_axisym_gradient(const Quad4Vectors& x) {
  const double r0 = x[0].x(), r1 = x[1].x(), r2 = x[2].x(), r3 = x[3].x();
  const double z0 = x[0].y(), z1 = x[1].y(), z2 = x[2].y(), z3 = x[3].y();
  Quad4Gradient g;
  const double two_a = (r0 - r2) * (z1 - z3) + (r1 - r3) * (z2 - z0);
  g.area = 0.5 * two_a;
  g.rbar = 0.25 * ((r0 + r1) + (r2 + r3));
  g.volume = g.rbar * g.area;
  const double inv = two_a != 0.0 ? 1.0 / two_a : 0.0;
  g.b[0] = inv * Vec2(z1 - z3, r3 - r1);
  g.b[1] = inv * Vec2(z2 - z0, r0 - r2);
  g.b[2] = inv * Vec2(z3 - z1, r1 - r3);
  g.b[3] = inv * Vec2(z0 - z2, r2 - r0);
  return g;
}

double quad4_axisym_characteristic_length(const Quad4Vectors& x, double area) {
  const double d2 = std::max((x[2] - x[0]).squaredNorm(), (x[3] - x[1]).squaredNorm());
  return d2 > 0.0 ? area / std::sqrt(d2) : 0.0;
}

std::array<double, 4> quad4_axisym_hourglass_vector(const Quad4Vectors& x, const Quad4Gradient& g) {
  constexpr double base[4] = {1.0, -1.0, 1.0, -1.0};
  const Vec2 h = (x[0] - x[1]) + (x[2] - x[3]);  // sum_b Gamma_b x_b
  std::array<double, 4> gamma;
  for (int a = 0; a < 4; ++a) gamma[a] = base[a] - h.dot(g.b[a]);
  return gamma;
}

double quad4_axisym_hourglass_viscous(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                      double a_h, Quad4Vectors& f) {
  Vec2 qdot = Vec2::Zero();
  for (int a = 0; a < 4; ++a) qdot += gamma[a] * v[a];
  const Vec2 Q = a_h * qdot;
  for (int a = 0; a < 4; ++a) f[a] -= gamma[a] * Q;
  return a_h * qdot.squaredNorm();
}

double quad4_axisym_hourglass_stiffness(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                        double kappa, double dt, const Mat2& R, Vec2& Q,
                                        Quad4Vectors& f) {
  Vec2 qdot = Vec2::Zero();
  for (int a = 0; a < 4; ++a) qdot += gamma[a] * v[a];
  Q = R * Q + (kappa * dt) * qdot;
  for (int a = 0; a < 4; ++a) f[a] -= gamma[a] * Q;
  return Q.dot(qdot);
}

}  // namespace splat
