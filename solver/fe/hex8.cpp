#include "solver/fe/hex8.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace splat {

namespace {

Hex8Field to_cm(const std::array<Vec3, 8>& v) {
  Hex8Field f;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) f.u[i][a] = v[a][i];
  return f;
}

std::array<Vec3, 8> from_cm(const Hex8Field& f) {
  std::array<Vec3, 8> v;
  for (int a = 0; a < 8; ++a) v[a] = Vec3(f.u[0][a], f.u[1][a], f.u[2][a]);
  return v;
}

Hex8GeometryCm to_cm(const Hex8Geometry& g) {
  Hex8GeometryCm c;
  for (int u = 0; u < 6; ++u)
    for (int i = 0; i < 3; ++i) c.g[u][i] = g.g[u][i];
  c.volume = g.volume;
  return c;
}

}  // namespace

Hex8Modes hex8_modes(const Hex8Vectors& u) {
  return {from_cm(hex8_modes_cm(to_cm(u)))};
}

Hex8Vectors hex8_nodal(const Hex8Modes& m) {
  return from_cm(hex8_nodal_cm(to_cm(m.c)));
}

Hex8Geometry hex8_geometry(const Hex8Modes& x) {
  const Hex8GeometryCm c = hex8_geometry_cm(to_cm(x.c));
  Hex8Geometry g;
  g.x = x;
  for (int u = 0; u < 6; ++u) g.g[u] = Vec3(c.g[u][0], c.g[u][1], c.g[u][2]);
  g.volume = c.volume;
  return g;
}

Mat3 hex8_velocity_gradient(const Hex8Modes& w, const Hex8Geometry& g) {
  return hex8_velocity_gradient_cm(to_cm(w.c), to_cm(g));
}

std::array<Vec3, 4> hex8_hourglass_rates(const Hex8Modes& w, const Hex8Modes& x, const Mat3& L) {
  return hex8_hourglass_rates_cm(to_cm(w.c), to_cm(x.c), L);
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
  return from_cm(hex8_forces_cm(sigma, to_cm(g), to_cm(x.c), Q));
}

double hex8_characteristic_length(const Hex8Vectors& x, double volume) {
  return hex8_characteristic_length_cm(to_cm(x), volume);
}

}  // namespace splat
