#include "solver/sph/sph_boundary.hpp"

#include <cmath>
#include <stdexcept>

#include "solver/mesh/mesh.hpp"

namespace splat {

SphAbsorbing make_sph_absorbing(const SphBody& body, const NodeSet& nodes, std::uint32_t on,
                                double layer_thickness, bool shear) {
  if (!(layer_thickness > 0.0)) {
    throw std::invalid_argument("absorbing layer: layer thickness must be > 0");
  }
  SphAbsorbing a;
  a.rho_cp = body.material.density * body.constants.wave_speed;
  a.rho_cs = shear ? std::sqrt(body.material.density * body.constants.G) : 0.0;
  struct Face {
    std::uint32_t bit;
    Vec3 normal;
  };
  const Face faces[] = {{boundary_x_min, Vec3(-1, 0, 0)}, {boundary_x_max, Vec3(1, 0, 0)},
                        {boundary_y_min, Vec3(0, -1, 0)}, {boundary_y_max, Vec3(0, 1, 0)},
                        {boundary_z_min, Vec3(0, 0, -1)}, {boundary_z_max, Vec3(0, 0, 1)},
                        {boundary_curved, Vec3::Zero()}};
  for (std::size_t i = 0; i < body.size(); ++i) {
    const std::size_t g = body.node_begin + i;
    for (const Face& f : faces) {
      if (!(on & f.bit) || !(nodes.boundary[g] & f.bit)) continue;
      const Vec3 n = f.bit == boundary_curved ? body.outward_normal[i] : f.normal;
      if (n.squaredNorm() == 0.0) continue;
      a.node.push_back(static_cast<int>(g));
      a.normal.push_back(n);
      a.area.push_back(body.volume0[i] / layer_thickness);
    }
  }
  return a;
}

double apply_sph_absorbing(const SphAbsorbing& a, NodeSet& nodes) {
  double power = 0.0;
  for (std::size_t k = 0; k < a.node.size(); ++k) {
    const std::size_t g = static_cast<std::size_t>(a.node[k]);
    const Vec3& v = nodes.v[g];
    const Vec3& n = a.normal[k];
    const double vn = v.dot(n);
    const Vec3 f = -a.area[k] * (a.rho_cp * vn * n + a.rho_cs * (v - vn * n));
    nodes.f[g] += f;
    power -= f.dot(v);
  }
  return power;
}

}  // namespace splat
