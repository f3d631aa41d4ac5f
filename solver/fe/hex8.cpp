#include "solver/fe/hex8.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace splat {

namespace {

// Faces of the unit cube by their node indices, in cyclic order.
constexpr int hex_faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace

Hex8Modes hex8_modes(const Hex8Vectors& u) {
  Hex8Modes m;
  for (int i = 0; i < 3; ++i) {
    // Butterflies (lo, hi) -> (hi + lo, hi - lo) along xi, then eta, then zeta.
    const double s01 = u[1][i] + u[0][i], d01 = u[1][i] - u[0][i];  // eta -, zeta -
    const double s32 = u[2][i] + u[3][i], d32 = u[2][i] - u[3][i];  // eta +, zeta -
    const double s45 = u[5][i] + u[4][i], d45 = u[5][i] - u[4][i];  // eta -, zeta +
    const double s76 = u[6][i] + u[7][i], d76 = u[6][i] - u[7][i];  // eta +, zeta +
    const double ss0 = s32 + s01, sd0 = s32 - s01, ds0 = d32 + d01, dd0 = d32 - d01;
    const double ss1 = s76 + s45, sd1 = s76 - s45, ds1 = d76 + d45, dd1 = d76 - d45;
    m.c[0][i] = 0.125 * (ss1 + ss0);
    m.c[1][i] = 0.125 * (ds1 + ds0);  // xi
    m.c[2][i] = 0.125 * (sd1 + sd0);  // eta
    m.c[3][i] = 0.125 * (ss1 - ss0);  // zeta
    m.c[4][i] = 0.125 * (sd1 - sd0);  // eta zeta
    m.c[5][i] = 0.125 * (ds1 - ds0);  // xi zeta
    m.c[6][i] = 0.125 * (dd1 + dd0);  // xi eta
    m.c[7][i] = 0.125 * (dd1 - dd0);  // xi eta zeta
  }
  return m;
}

Hex8Vectors hex8_nodal(const Hex8Modes& m) {
  Hex8Vectors u;
  for (int i = 0; i < 3; ++i) {
    // The butterflies of hex8_modes backwards: (even, odd) -> (even - odd, even + odd).
    const double ss0 = m.c[0][i] - m.c[3][i], ss1 = m.c[0][i] + m.c[3][i];
    const double sd0 = m.c[2][i] - m.c[4][i], sd1 = m.c[2][i] + m.c[4][i];
    const double ds0 = m.c[1][i] - m.c[5][i], ds1 = m.c[1][i] + m.c[5][i];
    const double dd0 = m.c[6][i] - m.c[7][i], dd1 = m.c[6][i] + m.c[7][i];
    const double s01 = ss0 - sd0, s32 = ss0 + sd0, d01 = ds0 - dd0, d32 = ds0 + dd0;
    const double s45 = ss1 - sd1, s76 = ss1 + sd1, d45 = ds1 - dd1, d76 = ds1 + dd1;
    u[0][i] = s01 - d01;
    u[1][i] = s01 + d01;
    u[3][i] = s32 - d32;
    u[2][i] = s32 + d32;
    u[4][i] = s45 - d45;
    u[5][i] = s45 + d45;
    u[7][i] = s76 - d76;
    u[6][i] = s76 + d76;
  }
  return u;
}

Hex8Geometry hex8_geometry(const Hex8Modes& x) {
  Hex8Geometry g;
  const Vec3& e1 = x.c[1];
  const Vec3& e2 = x.c[2];
  const Vec3& e3 = x.c[3];
  const Vec3& h1 = x.c[4];
  const Vec3& h2 = x.c[5];
  const Vec3& h3 = x.c[6];
  constexpr double third = 1.0 / 3.0;
  const Vec3 h32 = h3.cross(h2);
  const Vec3 h13 = h1.cross(h3);
  const Vec3 h21 = h2.cross(h1);
  g.g[0] = 8.0 * (e2.cross(e3) + third * h32);
  g.g[1] = 8.0 * (e3.cross(e1) + third * h13);
  g.g[2] = 8.0 * (e1.cross(e2) + third * h21);
  g.g[3] = (8.0 * third) * (e3.cross(h2) + h3.cross(e2));
  g.g[4] = (8.0 * third) * (e1.cross(h3) + h1.cross(e3));
  g.g[5] = (8.0 * third) * (h2.cross(e1) + e2.cross(h1));
  // V = e_1 . g_1 + (8/3) [h_2 . (h_1 x e_3) + h_3 . (e_2 x h_1)]
  //   = e_1 . g_1 + h_1 . (e_3 x h_2 + h_3 x e_2) (8/3) = e_1 . g_1 + h_1 . g_4.
  g.volume = e1.dot(g.g[0]) + h1.dot(g.g[3]);
  return g;
}

Hex8Gradient hex8_gradient(const Hex8Vectors& x) {
  const Hex8Geometry geo = hex8_geometry(hex8_modes(x));
  Hex8Modes m;
  m.c[0].setZero();
  m.c[7].setZero();
  const double s = geo.volume != 0.0 ? 0.125 / geo.volume : 0.0;
  for (int u = 1; u <= 6; ++u) m.c[u] = s * geo.g[u - 1];
  Hex8Gradient out;
  out.b = hex8_nodal(m);
  out.volume = geo.volume;
  return out;
}

Hex8Vectors hex8_forces(const Mat3& sigma, const Hex8Geometry& g, const Hex8Modes& x,
                        const std::array<Vec3, 4>& Q) {
  // f_a = -V sigma b_a - sum_k (Gamma^k_a - 8 h_k . b_a) Q^k
  //     = sum_{u=1..6} s_u(a) F_u - sum_k s_{3+k}(a) Q^k,
  // F_u = -S g_u, S = (sigma - M / V) / 8, M = 8 sum_k Q^k (x) h_k.
  // Written out in scalars: Eigen's mixed 2+1 packets for 3-vectors cost
  // store-forwarding stalls here.
  const double inv_v = 1.0 / g.volume;
  double S[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double m =
          Q[0][i] * x.c[4][j] + Q[1][i] * x.c[5][j] + Q[2][i] * x.c[6][j] + Q[3][i] * x.c[7][j];
      S[i][j] = 0.125 * sigma(i, j) - m * inv_v;
    }
  }
  Hex8Modes F;
  for (int i = 0; i < 3; ++i) {
    F.c[0][i] = 0.0;
    for (int u = 1; u <= 6; ++u) {
      const Vec3& gu = g.g[u - 1];
      F.c[u][i] = -(S[i][0] * gu[0] + S[i][1] * gu[1] + S[i][2] * gu[2]);
    }
    for (int k = 0; k < 3; ++k) F.c[4 + k][i] -= Q[k][i];
    F.c[7][i] = -Q[3][i];
  }
  return hex8_nodal(F);
}

double hex8_characteristic_length(const Hex8Vectors& x, double volume) {
  double max_area2 = 0.0;  // (2 A)^2
  for (const auto& fc : hex_faces) {
    const Vec3 d1 = x[fc[2]] - x[fc[0]];
    const Vec3 d2 = x[fc[3]] - x[fc[1]];
    max_area2 = std::max(max_area2, d1.cross(d2).squaredNorm());
  }
  return max_area2 > 0.0 ? 2.0 * volume / std::sqrt(max_area2) : 0.0;
}

}  // namespace splat
