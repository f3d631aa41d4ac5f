// 8-node hexahedron with one-point (mean-quadrature) integration and
// Flanagan-Belytschko hourglass control (Flanagan & Belytschko 1981, "A
// uniform strain hexahedron and quadrilateral with orthogonal hourglass
// control", IJNME 17, 679-706; FB below). Pure functions of nodal positions
// and velocities; the loop over elements lives in fe_body.cpp.
//
// Node order is that of the unit cube (mesh.hpp): in natural coordinates
// xi_a = (+-1, +-1, +-1) with node 0 = (-1,-1,-1), 1 = (1,-1,-1), 2 = (1,1,-1),
// 3 = (-1,1,-1), 4..7 the same at zeta = +1.
//
// Modes. A nodal field u_a is expanded in the eight nodal sign patterns
//   s_u(a) = 1, xi, eta, zeta, eta zeta, xi zeta, xi eta, xi eta zeta (u = 0..7)
// as u_a = sum_u s_u(a) c_u with c_u = (1/8) sum_a s_u(a) u_a (an 8-point
// Walsh-Hadamard transform, 24 vector additions). For the positions, c_1..c_3
// = e_1..e_3 are half the mean edge vectors along xi, eta, zeta and
// c_4..c_7 = h_1..h_4 the hourglass components (FB's Gamma^k . x / 8).
//
// Exact volume. Integrating det[x_xi, x_eta, x_zeta] over the cube (every
// monomial with an odd power integrates to zero):
//   V = 8 e_1.(e_2 x e_3) + (8/3) [e_1.(h_3 x h_2) + h_2.(h_1 x e_3) + h_3.(e_2 x h_1)],
// equal to 2x2x2 Gauss quadrature of det J and independent of h_4.
//
// Uniform gradient (FB): b_a = (1/V) int_V dN_a/dx dV = (1/V) dV/dx_a
// = (1/(8V)) sum_{u=1..6} s_u(a) g_u with g_u = dV/dc_u:
//   g_1 = 8 e_2 x e_3 + (8/3) h_3 x h_2,   g_4 = (8/3) (e_3 x h_2 + h_3 x e_2),
//   g_2 = 8 e_3 x e_1 + (8/3) h_1 x h_3,   g_5 = (8/3) (e_1 x h_3 + h_1 x e_3),
//   g_3 = 8 e_1 x e_2 + (8/3) h_2 x h_1,   g_6 = (8/3) (h_2 x e_1 + e_2 x h_1),
// so sum_a b_a = 0 and sum_a x_a (x) b_a = I hold to rounding on any element.
// Then, with v's modes w_u,
//   velocity gradient     L   = sum_a v_a (x) b_a = (1/V) sum_u w_u (x) g_u,
//   internal force        f_a = -V sigma b_a,
//   characteristic length L_c = V / (largest face area)           (LS-DYNA),
// with a face area 0.5 |d_1 x d_2| from its diagonals (exact for a planar
// face, the projected area of a warped one).
//
// Hourglass control. Base vectors Gamma^k_a = s_{3+k}(a), k = 1..4, made
// orthogonal to every linear field (FB):
//   gamma^k_a = Gamma^k_a - (sum_b Gamma^k_b x_b) . b_a = Gamma^k_a - 8 h_k . b_a,
// generalised hourglass rates qdot^k = sum_a gamma^k_a v_a = 8 (w_{3+k} - L h_k)
// (L on the same geometry), and with generalised forces Q^k
//   f_a = -sum_k gamma^k_a Q^k,
//   viscous   (as LS-DYNA type 3):  Q^k = a_h qdot^k,  a_h = c_hg rho c V^(2/3) / 4,
//   stiffness (as LS-DYNA type 5):  Q^k_{n+1} = R Q^k_n + kappa dt qdot^k,
//                                kappa = c_hg G_d V^(1/3) / 4,
// c_hg the hourglass coefficient (default 0.1), rho the current density, c the
// P-wave speed, G_d = (1 - D) G the damaged shear modulus, R the incremental
// Hughes-Winget rotation (the generalised forces co-rotate with the material).
// gamma is unnormalised (|Gamma^k|^2 = 8) as in LS-DYNA: on a cube of side h a
// mode of nodal amplitude v_0 (u_0) meets a nodal force 2 c_hg rho c h^2 v_0
// (2 c_hg G_d h u_0), c_hg times twice the impedance (stiffness) of a face.
// The power the hourglass forces absorb is P = -sum_a f_a . v_a
// = sum_k Q^k . qdot^k (>= 0 for the viscous form).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "solver/common/types.hpp"

namespace splat {

using Hex8Vectors = std::array<Vec3, 8>;

// Coefficients c_u of a nodal vector field in the eight sign patterns.
struct Hex8Modes {
  std::array<Vec3, 8> c;
};

// c_u = (1/8) sum_a s_u(a) u_a.
Hex8Modes hex8_modes(const Hex8Vectors& u);

// u_a = sum_u s_u(a) c_u (the inverse of hex8_modes).
Hex8Vectors hex8_nodal(const Hex8Modes& m);

// Geometry of one element in mode form.
struct Hex8Geometry {
  Hex8Modes x;            // modes of the nodal positions, m
  std::array<Vec3, 6> g;  // g_u = dV/dc_u for u = 1..6, m^2
  double volume = 0.0;    // exact volume, m^3 (<= 0: inverted)
};

Hex8Geometry hex8_geometry(const Hex8Modes& x);

// Explicit mean gradient b_a and volume (set-up, tests).
struct Hex8Gradient {
  Hex8Vectors b;        // 1/m
  double volume = 0.0;  // m^3
};
Hex8Gradient hex8_gradient(const Hex8Vectors& x);

// L = (1/V) sum_u w_u (x) g_u, 1/s.
inline Mat3 hex8_velocity_gradient(const Hex8Modes& w, const Hex8Geometry& g) {
  Mat3 L = w.c[1] * g.g[0].transpose();
  for (int u = 2; u <= 6; ++u) L.noalias() += w.c[u] * g.g[u - 1].transpose();
  return L * (1.0 / g.volume);  // one division, not nine
}

// L = sum_a v_a (x) b_a, 1/s.
inline Mat3 hex8_velocity_gradient(const Hex8Vectors& v, const Hex8Gradient& g) {
  Mat3 L = v[0] * g.b[0].transpose();
  for (int a = 1; a < 8; ++a) L.noalias() += v[a] * g.b[a].transpose();
  return L;
}

// qdot^k = 8 (w_{3+k} - L h_k), k = 1..4, from the modes w of the velocities
// and x of the positions, L the velocity gradient on that geometry, m/s.
inline std::array<Vec3, 4> hex8_hourglass_rates(const Hex8Modes& w, const Hex8Modes& x,
                                                const Mat3& L) {
  std::array<Vec3, 4> qdot;
  for (int k = 0; k < 4; ++k) qdot[k] = 8.0 * (w.c[4 + k] - L * x.c[4 + k]);
  return qdot;
}

// f_a = -V sigma b_a - sum_k gamma^k_a Q^k on the geometry g of positions
// with modes x, N.
Hex8Vectors hex8_forces(const Mat3& sigma, const Hex8Geometry& g, const Hex8Modes& x,
                        const std::array<Vec3, 4>& Q);

// L_c = V / (largest face area), m.
double hex8_characteristic_length(const Hex8Vectors& x, double volume);

// Cube root of a positive normal number to 1e-14 relative: a bit-level
// estimate (exponent divided by 3, within ~3 %) refined by two Halley steps
// y <- y (y^3 + 2 x) / (2 y^3 + x) (cubic convergence). A sixth of the cost of
// std::cbrt, which was a visible part of the element loop.
inline double cbrt_positive(double x) {
  double y = std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) / 3 + 0x2A9F7893782DA1CEull);
  for (int i = 0; i < 2; ++i) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y;
}

// a_h = c_hg rho c V^(2/3) / 4, kg/s.
inline double hex8_viscous_hourglass_coefficient(double c_hg, double rho, double c, double volume) {
  const double h = cbrt_positive(volume);
  return 0.25 * c_hg * rho * c * h * h;
}

// kappa = c_hg G_d V^(1/3) / 4, N/m.
inline double hex8_stiffness_hourglass_coefficient(double c_hg, double G_d, double volume) {
  return 0.25 * c_hg * G_d * cbrt_positive(volume);
}

// Viscous form: Q^k = a_h qdot^k; returns the absorbed power a_h sum |qdot^k|^2, W.
inline double hex8_hourglass_viscous(const std::array<Vec3, 4>& qdot, double a_h,
                                     std::array<Vec3, 4>& Q) {
  double power = 0.0;
  for (int k = 0; k < 4; ++k) {
    Q[k] = a_h * qdot[k];
    power += Q[k].dot(qdot[k]);
  }
  return power;
}

// Stiffness form: Q^k <- R Q^k + kappa dt qdot^k; returns sum Q^k . qdot^k
// (either sign: stored elastic energy comes back), W.
inline double hex8_hourglass_stiffness(const std::array<Vec3, 4>& qdot, double kappa, double dt,
                                       const Mat3& R, std::array<Vec3, 4>& Q) {
  double power = 0.0;
  for (int k = 0; k < 4; ++k) {
    Q[k] = R * Q[k] + (kappa * dt) * qdot[k];
    power += Q[k].dot(qdot[k]);
  }
  return power;
}

}  // namespace splat
