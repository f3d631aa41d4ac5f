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

#include "solver/common/simd_lanes.hpp"
#include "solver/common/types.hpp"

namespace splat {

using Quad4Vectors = std::array<Vec2, 4>;

// Component-major forms used by the element loop (fe_body.cpp); the Eigen
// forms below convert to and from them, so both run the same arithmetic.
// u[0][a] = r and u[1][a] = z component at node a. Written in scalars:
// building Eigen 2-vectors from two scalars made GCC store both and reload
// them as one packet, a store-forwarding stall per vector.
template <class T>
struct Quad4FieldT {
  T u[2][4];
};
using Quad4Field = Quad4FieldT<double>;

template <class T>
struct Quad4GradientCmT {
  T b[2][4];  // mean area gradient: b[0][a] = d/dr, b[1][a] = d/dz, 1/m
  T area;     // signed area, m^2 (<= 0: inverted)
  T rbar;     // mean nodal radius, m
  T volume;   // rbar A, m^3 per radian
};
using Quad4GradientCm = Quad4GradientCmT<double>;

template <class T>
SPLAT_LANE_INLINE Quad4GradientCmT<T> quad4_axisym_gradient_cm(const Quad4FieldT<T>& x) {
  const T r0 = x.u[0][0], r1 = x.u[0][1], r2 = x.u[0][2], r3 = x.u[0][3];
  const T z0 = x.u[1][0], z1 = x.u[1][1], z2 = x.u[1][2], z3 = x.u[1][3];
  Quad4GradientCmT<T> g;
  const T two_a = (r0 - r2) * (z1 - z3) + (r1 - r3) * (z2 - z0);
  g.area = 0.5 * two_a;
  g.rbar = 0.25 * ((r0 + r1) + (r2 + r3));
  g.volume = g.rbar * g.area;
  const T inv = lane_if_nonzero(two_a, 1.0 / two_a);
  g.b[0][0] = inv * (z1 - z3);
  g.b[1][0] = inv * (r3 - r1);
  g.b[0][1] = inv * (z2 - z0);
  g.b[1][1] = inv * (r0 - r2);
  g.b[0][2] = inv * (z3 - z1);
  g.b[1][2] = inv * (r1 - r3);
  g.b[0][3] = inv * (z0 - z2);
  g.b[1][3] = inv * (r2 - r0);
  return g;
}

// In-plane velocity gradient L2[i][j] and hoop rate L_thth, 1/s.
template <class T>
SPLAT_LANE_INLINE void quad4_axisym_velocity_gradient_cm(const Quad4FieldT<T>& v,
                                                         const Quad4GradientCmT<T>& g, T L2[2][2],
                                                         T& L_thth) {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      T sum = v.u[i][0] * g.b[j][0];
      for (int a = 1; a < 4; ++a) sum += v.u[i][a] * g.b[j][a];
      L2[i][j] = sum;
    }
  }
  const T vr = ((v.u[0][0] + v.u[0][1]) + v.u[0][2]) + v.u[0][3];
  L_thth = lane_if_positive(g.rbar, 0.25 * vr / g.rbar);
}

// 3x3 velocity gradient, components (r, z, theta), 1/s.
inline Mat3 quad4_axisym_velocity_gradient_cm(const Quad4Field& v, const Quad4GradientCm& g) {
  double L2[2][2], L_thth;
  quad4_axisym_velocity_gradient_cm(v, g, L2, L_thth);
  Mat3 L;
  L << L2[0][0], L2[0][1], 0.0,  //
      L2[1][0], L2[1][1], 0.0,   //
      0.0, 0.0, L_thth;
  return L;
}

// Internal forces per radian from the (r, z, theta) Cauchy stress components
// s_rr, s_rz, s_zr, s_zz, s_thth (overwrites f), N.
template <class T>
SPLAT_LANE_INLINE void quad4_axisym_stress_forces_cm(const T& s_rr, const T& s_rz, const T& s_zr,
                                                     const T& s_zz, const T& s_thth,
                                                     const Quad4GradientCmT<T>& g,
                                                     Quad4FieldT<T>& f) {
  const T V = g.volume;
  const T hoop = 0.25 * s_thth * g.area;
  for (int a = 0; a < 4; ++a) {
    const T br = g.b[0][a], bz = g.b[1][a];
    f.u[0][a] = -V * (s_rr * br + s_rz * bz) - hoop;
    f.u[1][a] = -V * (s_zr * br + s_zz * bz);
  }
}
inline void quad4_axisym_stress_forces_cm(const Mat3& sigma, const Quad4GradientCm& g,
                                          Quad4Field& f) {
  quad4_axisym_stress_forces_cm(sigma(0, 0), sigma(0, 1), sigma(1, 0), sigma(1, 1), sigma(2, 2), g,
                                f);
}

// L_c = A / max(|x_2 - x_0|, |x_3 - x_1|), m.
template <class T>
SPLAT_LANE_INLINE T quad4_axisym_characteristic_length_cm(const Quad4FieldT<T>& x, const T& area) {
  const T dr0 = x.u[0][2] - x.u[0][0], dz0 = x.u[1][2] - x.u[1][0];
  const T dr1 = x.u[0][3] - x.u[0][1], dz1 = x.u[1][3] - x.u[1][1];
  const T d2 = lane_max(dr0 * dr0 + dz0 * dz0, dr1 * dr1 + dz1 * dz1);
  return lane_if_positive(d2, area / lane_sqrt(d2));
}

// gamma_a of the single hourglass mode, -.
template <class T>
SPLAT_LANE_INLINE std::array<T, 4> quad4_axisym_hourglass_vector_cm(const Quad4FieldT<T>& x,
                                                                    const Quad4GradientCmT<T>& g) {
  constexpr double base[4] = {1.0, -1.0, 1.0, -1.0};
  T h[2];  // sum_b Gamma_b x_b
  for (int i = 0; i < 2; ++i) h[i] = (x.u[i][0] - x.u[i][1]) + (x.u[i][2] - x.u[i][3]);
  std::array<T, 4> gamma;
  for (int a = 0; a < 4; ++a) gamma[a] = base[a] - (h[0] * g.b[0][a] + h[1] * g.b[1][a]);
  return gamma;
}

// qdot = sum_a gamma_a v_a, m/s.
template <class T>
SPLAT_LANE_INLINE void quad4_axisym_hourglass_rate_cm(const std::array<T, 4>& gamma,
                                                      const Quad4FieldT<T>& v, T qdot[2]) {
  for (int i = 0; i < 2; ++i) {
    T sum = T{};
    for (int a = 0; a < 4; ++a) sum += gamma[a] * v.u[i][a];
    qdot[i] = sum;
  }
}

// Adds the viscous hourglass forces; returns a_h |qdot|^2 >= 0, W per radian.
template <class T>
SPLAT_LANE_INLINE T quad4_axisym_hourglass_viscous_cm(const std::array<T, 4>& gamma,
                                                      const Quad4FieldT<T>& v, const T& a_h,
                                                      Quad4FieldT<T>& f) {
  T qdot[2];
  quad4_axisym_hourglass_rate_cm(gamma, v, qdot);
  const T Q[2] = {a_h * qdot[0], a_h * qdot[1]};
  for (int i = 0; i < 2; ++i)
    for (int a = 0; a < 4; ++a) f.u[i][a] -= gamma[a] * Q[i];
  return a_h * (qdot[0] * qdot[0] + qdot[1] * qdot[1]);
}

// Rotates Q (N per radian) by the in-plane rotation R (the (r, z) block of a
// 3x3 rotation), adds kappa dt qdot, adds f_a = -gamma_a Q; returns the
// mid-point power (R Q_old + Q_new) / 2 . qdot, W per radian (as
// hex8_hourglass_stiffness).
template <class T>
SPLAT_LANE_INLINE T quad4_axisym_hourglass_stiffness_cm(const std::array<T, 4>& gamma,
                                                        const Quad4FieldT<T>& v, const T& kappa,
                                                        double dt, const T& R00, const T& R01,
                                                        const T& R10, const T& R11, T Q[2],
                                                        Quad4FieldT<T>& f) {
  T qdot[2];
  quad4_axisym_hourglass_rate_cm(gamma, v, qdot);
  const T rotated0 = R00 * Q[0] + R01 * Q[1];
  const T rotated1 = R10 * Q[0] + R11 * Q[1];
  Q[0] = rotated0 + (kappa * dt) * qdot[0];
  Q[1] = rotated1 + (kappa * dt) * qdot[1];
  for (int i = 0; i < 2; ++i)
    for (int a = 0; a < 4; ++a) f.u[i][a] -= gamma[a] * Q[i];
  return 0.5 * ((rotated0 + Q[0]) * qdot[0] + (rotated1 + Q[1]) * qdot[1]);
}
inline double quad4_axisym_hourglass_stiffness_cm(const std::array<double, 4>& gamma,
                                                  const Quad4Field& v, double kappa, double dt,
                                                  const Mat3& R, double Q[2], Quad4Field& f) {
  return quad4_axisym_hourglass_stiffness_cm(gamma, v, kappa, dt, R(0, 0), R(0, 1), R(1, 0),
                                             R(1, 1), Q, f);
}

struct Quad4Gradient {
  Quad4Vectors b;       // mean area gradient (d/dr, d/dz), 1/m
  double area = 0.0;    // signed area, m^2 (<= 0: inverted)
  double rbar = 0.0;    // mean nodal radius, m
  double volume = 0.0;  // rbar A, m^3 per radian
};

Quad4Gradient quad4_axisym_gradient(const Quad4Vectors& x);

// 3x3 velocity gradient, components (r, z, theta), 1/s.
Mat3 quad4_axisym_velocity_gradient(const Quad4Vectors& v, const Quad4Gradient& g);

// Internal forces per radian from the (r, z, theta) Cauchy stress (overwrites f), N.
void quad4_axisym_stress_forces(const Mat3& sigma, const Quad4Gradient& g, Quad4Vectors& f);

// L_c = A / max(|x_2 - x_0|, |x_3 - x_1|), m.
double quad4_axisym_characteristic_length(const Quad4Vectors& x, double area);

// gamma_a of the single hourglass mode, -.
std::array<double, 4> quad4_axisym_hourglass_vector(const Quad4Vectors& x, const Quad4Gradient& g);

// a_h = c_hg rho c rbar sqrt(A) / 2, kg/s per radian (T = double or lanes).
template <class T>
SPLAT_LANE_INLINE T quad4_axisym_viscous_hourglass_coefficient_t(double c_hg, const T& rho,
                                                                 double c, const T& rbar,
                                                                 const T& area) {
  return 0.5 * c_hg * rho * c * rbar * lane_sqrt(lane_max(area, T{}));
}
inline double quad4_axisym_viscous_hourglass_coefficient(double c_hg, double rho, double c,
                                                         double rbar, double area) {
  return quad4_axisym_viscous_hourglass_coefficient_t(c_hg, rho, c, rbar, area);
}
inline double quad4_axisym_viscous_hourglass_coefficient(double c_hg, double rho, double c,
                                                         const Quad4Gradient& g) {
  return quad4_axisym_viscous_hourglass_coefficient(c_hg, rho, c, g.rbar, g.area);
}

// kappa = c_hg G_d rbar / 2, N/m per radian.
inline double quad4_axisym_stiffness_hourglass_coefficient(double c_hg, double G_d, double rbar) {
  return 0.5 * c_hg * G_d * rbar;
}
inline double quad4_axisym_stiffness_hourglass_coefficient(double c_hg, double G_d,
                                                           const Quad4Gradient& g) {
  return quad4_axisym_stiffness_hourglass_coefficient(c_hg, G_d, g.rbar);
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
