#include "solver/fe/quad4_axisym.hpp"

#include <algorithm>

namespace splat {

namespace {

Quad4Field to_cm(const Quad4Vectors& v) {
  Quad4Field f;
  for (int a = 0; a < 4; ++a) {
    f.u[0][a] = v[a].x();
    f.u[1][a] = v[a].y();
  }
  return f;
}

Quad4Vectors from_cm(const Quad4Field& f) {
  Quad4Vectors v;
  for (int a = 0; a < 4; ++a) v[a] = Vec2(f.u[0][a], f.u[1][a]);
  return v;
}

Quad4GradientCm to_cm(const Quad4Gradient& g) {
  Quad4GradientCm c;
  for (int a = 0; a < 4; ++a) {
    c.b[0][a] = g.b[a].x();
    c.b[1][a] = g.b[a].y();
  }
  c.area = g.area;
  c.rbar = g.rbar;
  c.volume = g.volume;
  return c;
}

}  // namespace

Quad4Gradient quad4_axisym_gradient(const Quad4Vectors& x) {
  const Quad4GradientCm c = quad4_axisym_gradient_cm(to_cm(x));
  Quad4Gradient g;
  for (int a = 0; a < 4; ++a) g.b[a] = Vec2(c.b[0][a], c.b[1][a]);
  g.area = c.area;
  g.rbar = c.rbar;
  g.volume = c.volume;
  return g;
}

Mat3 quad4_axisym_velocity_gradient(const Quad4Vectors& v, const Quad4Gradient& g) {
  return quad4_axisym_velocity_gradient_cm(to_cm(v), to_cm(g));
}

void quad4_axisym_stress_forces(const Mat3& sigma, const Quad4Gradient& g, Quad4Vectors& f) {
  Quad4Field fc;
  quad4_axisym_stress_forces_cm(sigma, to_cm(g), fc);
  f = from_cm(fc);
}

double quad4_axisym_characteristic_length(const Quad4Vectors& x, double area) {
  return quad4_axisym_characteristic_length_cm(to_cm(x), area);
}

std::array<double, 4> quad4_axisym_hourglass_vector(const Quad4Vectors& x, const Quad4Gradient& g) {
  return quad4_axisym_hourglass_vector_cm(to_cm(x), to_cm(g));
}

double quad4_axisym_hourglass_viscous(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                      double a_h, Quad4Vectors& f) {
  Quad4Field fc = to_cm(f);
  const double power = quad4_axisym_hourglass_viscous_cm(gamma, to_cm(v), a_h, fc);
  f = from_cm(fc);
  return power;
}

double quad4_axisym_hourglass_stiffness(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                        double kappa, double dt, const Mat2& R, Vec2& Q,
                                        Quad4Vectors& f) {
  Mat3 R3 = Mat3::Identity();
  R3.topLeftCorner<2, 2>() = R;
  double q[2] = {Q.x(), Q.y()};
  Quad4Field fc = to_cm(f);
  const double power = quad4_axisym_hourglass_stiffness_cm(gamma, to_cm(v), kappa, dt, R3, q, fc);
  Q = Vec2(q[0], q[1]);
  f = from_cm(fc);
  return power;
}

}  // namespace splat
