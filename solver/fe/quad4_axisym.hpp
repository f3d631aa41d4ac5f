// 4-node axisymmetric quadrilateral in the (r, z) half-plane, one-point
// integration with the mean area gradient, volume-weighted (all volumes,
// masses and forces per radian), and Flanagan-Belytschko hourglass control.
// Pure functions; the loop over elements lives in fe_body.cpp.
//
// Nodes are counter-clockwise in (r, z) (mesh.hpp). With the bilinear area
//   A = 1/2 [(r_0 - r_2)(z_1 - z_3) + (r_1 - r_3)(z_2 - z_0)],
// the mean gradient b_a = (1/A) int_A dN_a/dx dA = (1/A) dA/dx_a is
//   b_r = (z_1 - z_3, z_2 - z_0, z_3 - z_1, z_0 - z_2) / (2A),
//   b_z = (r_3 - r_1, r_0 - r_2, r_1 - r_3, r_2 - r_0) / (2A),
// exact for any quadrilateral (sum_a x_a (x) b_a = I in the plane). The
// element volume per radian is V = rbar A with rbar the mean nodal radius.
// Velocity gradient, index 0 = r, 1 = z, 2 = theta:
//   L_rr = sum v_ar b_ar, L_rz = sum v_ar b_az, L_zr = sum v_az b_ar,
//   L_zz = sum v_az b_az, L_thth = vbar_r / rbar (vbar_r mean nodal v_r),
// so linear velocity fields are reproduced exactly in the plane and the hoop
// rate is v_r / r at the centroid of the nodes. Internal forces per radian
//   f_ar = -V (s_rr b_ar + s_rz b_az) - s_thth A / 4,
//   f_az = -V (s_rz b_ar + s_zz b_az),
// are the exact work conjugates of L: -sum_a f_a . v_a = V sigma : L.
//
// Characteristic length L_c = A / (longest diagonal): the one-point quad's
// highest single-element mode is the diagonal breathing mode, whose critical
// step on a square of side h is exactly h / (sqrt(2) c) = (A / diagonal) / c;
// on a parallelogram it never exceeds the smallest altitude (the longest
// diagonal is at least the longest side), so skewed elements are not
// over-estimated, and the margin over the plane-wave limit h / c covers the
// extra hoop stiffness of elements next to the axis.
//
// Hourglass control with the single mode Gamma = (1, -1, 1, -1) made
// orthogonal to linear fields (FB 1981, in 2D):
//   gamma_a = Gamma_a - (sum_b Gamma_b r_b) b_ar - (sum_b Gamma_b z_b) b_az,
// qdot = sum_a gamma_a v_a (an (r, z) vector),
//   viscous:   f_a = -a_h gamma_a qdot,             a_h = c_hg rho c rbar sqrt(A) / 2,
//   stiffness: Q_{n+1} = R Q_n + kappa dt qdot,    f_a = -gamma_a Q,
//              kappa = c_hg G_d rbar / 2.
// |Gamma|^2 = 4, so on a square of side h a mode of nodal amplitude v_0 (u_0)
// meets a nodal force 2 c_hg rho c (rbar h) v_0 (2 c_hg G_d rbar u_0): the same
// per unit face area (rbar h per radian) as the 3D hexahedron (hex8.hpp).
// Both return the absorbed power -sum_a f_a . v_a per radian.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/common/types.hpp"

namespace splat {

using Quad4Vectors = std::array<Vec2, 4>;

struct Quad4Gradient {
  Quad4Vectors b;       // mean area gradient (d/dr, d/dz), 1/m
  double area = 0.0;    // signed area, m^2 (<= 0: inverted)
  double rbar = 0.0;    // mean nodal radius, m
  double volume = 0.0;  // rbar A, m^3 per radian
};

Quad4Gradient quad4_axisym_gradient(const Quad4Vectors& x);

// 3x3 velocity gradient, components (r, z, theta), 1/s.
inline Mat3 quad4_axisym_velocity_gradient(const Quad4Vectors& v, const Quad4Gradient& g) {
  Mat2 L2 = v[0] * g.b[0].transpose();
  double vr = v[0].x();
  for (int a = 1; a < 4; ++a) {
    L2.noalias() += v[a] * g.b[a].transpose();
    vr += v[a].x();
  }
  Mat3 L = Mat3::Zero();
  L.topLeftCorner<2, 2>() = L2;
  L(2, 2) = g.rbar > 0.0 ? 0.25 * vr / g.rbar : 0.0;
  return L;
}

// Internal forces per radian from the (r, z, theta) Cauchy stress (overwrites f), N.
inline void quad4_axisym_stress_forces(const Mat3& sigma, const Quad4Gradient& g, Quad4Vectors& f) {
  const double V = g.volume;
  const double hoop = 0.25 * sigma(2, 2) * g.area;
  for (int a = 0; a < 4; ++a) {
    const Vec2& b = g.b[a];
    f[a] = Vec2(-V * (sigma(0, 0) * b.x() + sigma(0, 1) * b.y()) - hoop,
                -V * (sigma(1, 0) * b.x() + sigma(1, 1) * b.y()));
  }
}

// L_c = A / max(|x_2 - x_0|, |x_3 - x_1|), m.
double quad4_axisym_characteristic_length(const Quad4Vectors& x, double area);

// gamma_a of the single hourglass mode, -.
std::array<double, 4> quad4_axisym_hourglass_vector(const Quad4Vectors& x, const Quad4Gradient& g);

// a_h = c_hg rho c rbar sqrt(A) / 2, kg/s per radian.
inline double quad4_axisym_viscous_hourglass_coefficient(double c_hg, double rho, double c,
                                                         const Quad4Gradient& g) {
  return 0.5 * c_hg * rho * c * g.rbar * std::sqrt(std::max(g.area, 0.0));
}

// kappa = c_hg G_d rbar / 2, N/m per radian.
inline double quad4_axisym_stiffness_hourglass_coefficient(double c_hg, double G_d,
                                                           const Quad4Gradient& g) {
  return 0.5 * c_hg * G_d * g.rbar;
}

// Adds the viscous hourglass forces; returns a_h |qdot|^2 >= 0, W per radian.
double quad4_axisym_hourglass_viscous(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                      double a_h, Quad4Vectors& f);

// Rotates Q (N per radian) by the in-plane rotation R, adds kappa dt qdot,
// adds f_a = -gamma_a Q; returns Q . qdot, W per radian.
double quad4_axisym_hourglass_stiffness(const std::array<double, 4>& gamma, const Quad4Vectors& v,
                                        double kappa, double dt, const Mat2& R, Vec2& Q,
                                        Quad4Vectors& f);

}  // namespace splat
