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

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "solver/common/simd_lanes.hpp"
#include "solver/common/types.hpp"

namespace splat {

using Hex8Vectors = std::array<Vec3, 8>;

// Component-major forms used by the element loop (fe_body.cpp); the Eigen
// forms below convert to and from them, so both run the same arithmetic.
// A field u[i][a] holds component i at node a (or mode a). Written in
// scalars: Eigen's 3-vectors mix scalar stores with 2-wide packet loads of
// the same memory, and the store-forwarding stalls cost more than the
// arithmetic of a whole element. Each kernel is a template on the number type
// (simd_lanes.hpp).
template <class T>
struct Hex8FieldT {
  T u[3][8];
};
using Hex8Field = Hex8FieldT<double>;

// Geometry in mode form: g[u-1][j] = component j of g_u = dV/dc_u, u = 1..6.
template <class T>
struct Hex8GeometryCmT {
  T g[6][3];
  T volume;
};
using Hex8GeometryCm = Hex8GeometryCmT<double>;

// c_u = (1/8) sum_a s_u(a) u_a: butterflies (lo, hi) -> (hi + lo, hi - lo)
// along xi, then eta, then zeta.
template <class T>
SPLAT_LANE_INLINE Hex8FieldT<T> hex8_modes_cm(const Hex8FieldT<T>& n) {
  Hex8FieldT<T> m;
  for (int i = 0; i < 3; ++i) {
    const T* u = n.u[i];
    const T s01 = u[1] + u[0], d01 = u[1] - u[0];  // eta -, zeta -
    const T s32 = u[2] + u[3], d32 = u[2] - u[3];  // eta +, zeta -
    const T s45 = u[5] + u[4], d45 = u[5] - u[4];  // eta -, zeta +
    const T s76 = u[6] + u[7], d76 = u[6] - u[7];  // eta +, zeta +
    const T ss0 = s32 + s01, sd0 = s32 - s01, ds0 = d32 + d01, dd0 = d32 - d01;
    const T ss1 = s76 + s45, sd1 = s76 - s45, ds1 = d76 + d45, dd1 = d76 - d45;
    T* c = m.u[i];
    c[0] = 0.125 * (ss1 + ss0);
    c[1] = 0.125 * (ds1 + ds0);  // xi
    c[2] = 0.125 * (sd1 + sd0);  // eta
    c[3] = 0.125 * (ss1 - ss0);  // zeta
    c[4] = 0.125 * (sd1 - sd0);  // eta zeta
    c[5] = 0.125 * (ds1 - ds0);  // xi zeta
    c[6] = 0.125 * (dd1 + dd0);  // xi eta
    c[7] = 0.125 * (dd1 - dd0);  // xi eta zeta
  }
  return m;
}

// u_a = sum_u s_u(a) c_u: the butterflies backwards.
template <class T>
SPLAT_LANE_INLINE Hex8FieldT<T> hex8_nodal_cm(const Hex8FieldT<T>& m) {
  Hex8FieldT<T> n;
  for (int i = 0; i < 3; ++i) {
    const T* c = m.u[i];
    const T ss0 = c[0] - c[3], ss1 = c[0] + c[3];
    const T sd0 = c[2] - c[4], sd1 = c[2] + c[4];
    const T ds0 = c[1] - c[5], ds1 = c[1] + c[5];
    const T dd0 = c[6] - c[7], dd1 = c[6] + c[7];
    const T s01 = ss0 - sd0, s32 = ss0 + sd0, d01 = ds0 - dd0, d32 = ds0 + dd0;
    const T s45 = ss1 - sd1, s76 = ss1 + sd1, d45 = ds1 - dd1, d76 = ds1 + dd1;
    T* u = n.u[i];
    u[0] = s01 - d01;
    u[1] = s01 + d01;
    u[3] = s32 - d32;
    u[2] = s32 + d32;
    u[4] = s45 - d45;
    u[5] = s45 + d45;
    u[7] = s76 - d76;
    u[6] = s76 + d76;
  }
  return n;
}

// (a x b)_i of modes p and q of c. A function forced inline, not a lambda: a
// lambda returning a lane vector is compiled for the baseline target when
// it is not inlined (as in the sanitizer build) and then disagrees with its
// AVX-512 caller on how the vector is returned.
template <class T>
SPLAT_LANE_INLINE T hex8_mode_cross(const T (&c)[3][8], int p, int q, int i) {
  const int j = (i + 1) % 3, k = (i + 2) % 3;
  return c[j][p] * c[k][q] - c[k][p] * c[j][q];
}

// g_u and the exact volume from the position modes (formulas in the header
// comment above); only modes 1..6 are read.
template <class T>
SPLAT_LANE_INLINE Hex8GeometryCmT<T> hex8_geometry_cm(const Hex8FieldT<T>& x) {
  const auto& c = x.u;
  constexpr double third = 1.0 / 3.0;
  Hex8GeometryCmT<T> g;
  for (int i = 0; i < 3; ++i) {
    // modes: e1 = 1, e2 = 2, e3 = 3, h1 = 4, h2 = 5, h3 = 6
    g.g[0][i] = 8.0 * (hex8_mode_cross(c, 2, 3, i) + third * hex8_mode_cross(c, 6, 5, i));
    g.g[1][i] = 8.0 * (hex8_mode_cross(c, 3, 1, i) + third * hex8_mode_cross(c, 4, 6, i));
    g.g[2][i] = 8.0 * (hex8_mode_cross(c, 1, 2, i) + third * hex8_mode_cross(c, 5, 4, i));
    g.g[3][i] = (8.0 * third) * (hex8_mode_cross(c, 3, 5, i) + hex8_mode_cross(c, 6, 2, i));
    g.g[4][i] = (8.0 * third) * (hex8_mode_cross(c, 1, 6, i) + hex8_mode_cross(c, 4, 3, i));
    g.g[5][i] = (8.0 * third) * (hex8_mode_cross(c, 5, 1, i) + hex8_mode_cross(c, 2, 4, i));
  }
  // V = e_1 . g_1 + h_1 . g_4
  g.volume = (c[0][1] * g.g[0][0] + c[1][1] * g.g[0][1] + c[2][1] * g.g[0][2]) +
             (c[0][4] * g.g[3][0] + c[1][4] * g.g[3][1] + c[2][4] * g.g[3][2]);
  return g;
}

// L = (1/V) sum_u w_u (x) g_u, 1/s.
template <class T>
SPLAT_LANE_INLINE void hex8_velocity_gradient_cm(const Hex8FieldT<T>& w,
                                                 const Hex8GeometryCmT<T>& g, T L[3][3]) {
  const T inv_v = 1.0 / g.volume;  // one division, not nine
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      T sum = w.u[i][1] * g.g[0][j];
      for (int u = 2; u <= 6; ++u) sum += w.u[i][u] * g.g[u - 1][j];
      L[i][j] = sum * inv_v;
    }
  }
}
inline Mat3 hex8_velocity_gradient_cm(const Hex8Field& w, const Hex8GeometryCm& g) {
  double L[3][3];
  hex8_velocity_gradient_cm(w, g, L);
  Mat3 out;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) out(i, j) = L[i][j];
  return out;
}

// qdot^k = 8 (w_{3+k} - L h_k), k = 1..4, m/s (as hex8_hourglass_rates):
// qdot[k][i] is component i.
template <class T>
SPLAT_LANE_INLINE void hex8_hourglass_rates_cm(const Hex8FieldT<T>& w, const Hex8FieldT<T>& x,
                                               const T L[3][3], T qdot[4][3]) {
  for (int k = 0; k < 4; ++k) {
    const int u = 4 + k;
    for (int i = 0; i < 3; ++i) {
      const T lh = L[i][0] * x.u[0][u] + L[i][1] * x.u[1][u] + L[i][2] * x.u[2][u];
      qdot[k][i] = 8.0 * (w.u[i][u] - lh);
    }
  }
}
inline std::array<Vec3, 4> hex8_hourglass_rates_cm(const Hex8Field& w, const Hex8Field& x,
                                                   const Mat3& L) {
  double Lc[3][3], q[4][3];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) Lc[i][j] = L(i, j);
  hex8_hourglass_rates_cm(w, x, Lc, q);
  std::array<Vec3, 4> qdot;
  for (int k = 0; k < 4; ++k) qdot[k] = Vec3(q[k][0], q[k][1], q[k][2]);
  return qdot;
}

// f_a = -V sigma b_a - sum_k gamma^k_a Q^k (as hex8_forces), N; Q[k][i] is
// component i of Q^k.
template <class T>
SPLAT_LANE_INLINE Hex8FieldT<T> hex8_forces_cm(const T sigma[3][3], const Hex8GeometryCmT<T>& g,
                                               const Hex8FieldT<T>& x, const T Q[4][3]) {
  // f_a = sum_{u=1..6} s_u(a) F_u - sum_k s_{3+k}(a) Q^k,
  // F_u = -S g_u, S = (sigma - M / V) / 8, M = 8 sum_k Q^k (x) h_k.
  const T inv_v = 1.0 / g.volume;
  T S[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const T m =
          Q[0][i] * x.u[j][4] + Q[1][i] * x.u[j][5] + Q[2][i] * x.u[j][6] + Q[3][i] * x.u[j][7];
      S[i][j] = 0.125 * sigma[i][j] - m * inv_v;
    }
  }
  Hex8FieldT<T> F;
  for (int i = 0; i < 3; ++i) {
    F.u[i][0] = T{};
    for (int u = 1; u <= 6; ++u) {
      const T* gu = g.g[u - 1];
      F.u[i][u] = -(S[i][0] * gu[0] + S[i][1] * gu[1] + S[i][2] * gu[2]);
    }
    for (int k = 0; k < 3; ++k) F.u[i][4 + k] -= Q[k][i];
    F.u[i][7] = -Q[3][i];
  }
  return hex8_nodal_cm(F);
}
inline Hex8Field hex8_forces_cm(const Mat3& sigma, const Hex8GeometryCm& g, const Hex8Field& x,
                                const std::array<Vec3, 4>& Q) {
  double s[3][3], q[4][3];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) s[i][j] = sigma(i, j);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) q[k][i] = Q[k][i];
  return hex8_forces_cm(s, g, x, q);
}

// (2 A)^2 of the largest face (A its area from the diagonals), m^4.
template <class T>
SPLAT_LANE_INLINE T hex8_max_face_area2_cm(const Hex8FieldT<T>& x) {
  // Faces of the unit cube by their node indices, in cyclic order.
  constexpr int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  T max_area2 = T{};
  for (const auto& fc : faces) {
    T d1[3], d2[3];
    for (int i = 0; i < 3; ++i) {
      d1[i] = x.u[i][fc[2]] - x.u[i][fc[0]];
      d2[i] = x.u[i][fc[3]] - x.u[i][fc[1]];
    }
    const T n0 = d1[1] * d2[2] - d1[2] * d2[1];
    const T n1 = d1[2] * d2[0] - d1[0] * d2[2];
    const T n2 = d1[0] * d2[1] - d1[1] * d2[0];
    max_area2 = lane_max(max_area2, n0 * n0 + n1 * n1 + n2 * n2);
  }
  return max_area2;
}

// L_c = V / (largest face area), m (as hex8_characteristic_length).
inline double hex8_characteristic_length_cm(const Hex8Field& x, double volume) {
  const double max_area2 = hex8_max_face_area2_cm(x);
  return max_area2 > 0.0 ? 2.0 * volume / std::sqrt(max_area2) : 0.0;
}

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
Mat3 hex8_velocity_gradient(const Hex8Modes& w, const Hex8Geometry& g);

// L = sum_a v_a (x) b_a, 1/s.
inline Mat3 hex8_velocity_gradient(const Hex8Vectors& v, const Hex8Gradient& g) {
  Mat3 L = v[0] * g.b[0].transpose();
  for (int a = 1; a < 8; ++a) L.noalias() += v[a] * g.b[a].transpose();
  return L;
}

// qdot^k = 8 (w_{3+k} - L h_k), k = 1..4, from the modes w of the velocities
// and x of the positions, L the velocity gradient on that geometry, m/s.
std::array<Vec3, 4> hex8_hourglass_rates(const Hex8Modes& w, const Hex8Modes& x, const Mat3& L);

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
// The estimate and the steps are apart so that the element loop can take the
// estimate lane by lane and the steps on whole lanes (T = double or Lane<W>),
// to the same bits.
inline double cbrt_positive_estimate(double x) {
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) / 3 + 0x2A9F7893782DA1CEull);
}
template <class T>
SPLAT_LANE_INLINE T cbrt_positive_refine(const T& x, const T& estimate) {
  T y = estimate;
  for (int i = 0; i < 2; ++i) {
    const T y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y;
}
inline double cbrt_positive(double x) {
  return cbrt_positive_refine(x, cbrt_positive_estimate(x));
}

// a_h = c_hg rho c V^(2/3) / 4, kg/s, from h = V^(1/3) (T = double or lanes).
template <class T>
SPLAT_LANE_INLINE T hex8_viscous_hourglass_coefficient_of_cbrt(double c_hg, const T& rho, double c,
                                                               const T& h) {
  return 0.25 * c_hg * rho * c * h * h;
}
inline double hex8_viscous_hourglass_coefficient(double c_hg, double rho, double c, double volume) {
  return hex8_viscous_hourglass_coefficient_of_cbrt(c_hg, rho, c, cbrt_positive(volume));
}

// kappa = c_hg G_d V^(1/3) / 4, N/m, from h = V^(1/3).
inline double hex8_stiffness_hourglass_coefficient_of_cbrt(double c_hg, double G_d, double h) {
  return 0.25 * c_hg * G_d * h;
}
inline double hex8_stiffness_hourglass_coefficient(double c_hg, double G_d, double volume) {
  return hex8_stiffness_hourglass_coefficient_of_cbrt(c_hg, G_d, cbrt_positive(volume));
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

// Stiffness form: Q^k <- R Q^k + kappa dt qdot^k; returns the mid-point power
// sum (R Q^k_old + Q^k_new) / 2 . qdot^k (either sign: stored elastic energy
// comes back), W. The mid-point makes the booked work over a step equal the
// change of the stored energy |Q|^2 / (2 kappa) exactly; Q_new . qdot alone
// books an extra kappa dt |qdot|^2 every step, a drift of order dt.
inline double hex8_hourglass_stiffness(const std::array<Vec3, 4>& qdot, double kappa, double dt,
                                       const Mat3& R, std::array<Vec3, 4>& Q) {
  double power = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 rotated = R * Q[k];
    Q[k] = rotated + (kappa * dt) * qdot[k];
    const Vec3 mid = 0.5 * (rotated + Q[k]);
    power += mid.dot(qdot[k]);
  }
  return power;
}

}  // namespace splat
