#include "solver/sph/sph_boundary.hpp"

#include <cmath>
#include <stdexcept>

#include "solver/common/parallel.hpp"
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
  // An edge or corner particle has one entry per face, next to each other
  // (make_sph_absorbing). A block leaves the entries of the node its
  // predecessor ends with to that block and runs on to the last entry of its
  // own last node, so each node's forces are added by one thread, in entry
  // order.
  constexpr std::size_t block = 512;
  const std::size_t n = a.node.size();
  return block_sum(n, block, 2 * block, 0.0, [&](std::size_t first, std::size_t last) {
    while (first > 0 && first < last && a.node[first] == a.node[first - 1]) ++first;
    if (first == last) return 0.0;  // all entries belong to the previous block's node
    while (last < n && a.node[last] == a.node[last - 1]) ++last;
    double power = 0.0;
    for (std::size_t k = first; k < last; ++k) {
      const std::size_t g = static_cast<std::size_t>(a.node[k]);
      const Vec3& v = nodes.v[g];
      const Vec3& nk = a.normal[k];
      const double vn = v.dot(nk);
      const Vec3 f = -a.area[k] * (a.rho_cp * vn * nk + a.rho_cs * (v - vn * nk));
      nodes.f[g] += f;
      power -= f.dot(v);
    }
    return power;
  });
}

}  // namespace splat
