#include "solver/adhesion/interface_average.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace splat {
namespace {

using CellKey = std::int64_t;

// Cell (ix, iy, iz) packed in 21 bits per axis (indices wrap beyond +-1e6
// cells, which only merges far cells into one bucket: the distance test
// below still decides).
CellKey cell_key(long ix, long iy, long iz) {
  constexpr long k_half = 1L << 20;
  const auto wrap = [](long i) { return static_cast<CellKey>((i + k_half) & ((1L << 21) - 1)); };
  return (wrap(ix) << 42) | (wrap(iy) << 21) | wrap(iz);
}

struct CellGrid {
  double size = 0.0;  // m
  std::unordered_map<CellKey, std::vector<int>> cells;

  long index(double c) const { return static_cast<long>(std::floor(c / size)); }
};

CellGrid build_grid(const std::vector<MaterialSample>& samples, double length) {
  CellGrid g;
  g.size = length;
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const Vec3& x = samples[j].x;
    g.cells[cell_key(g.index(x.x()), g.index(x.y()), g.index(x.z()))].push_back(
        static_cast<int>(j));
  }
  return g;
}

InterfaceSideState average_one(const std::vector<MaterialSample>& samples, const CellGrid& g,
                               const Vec3& c, double length, const InterfaceSideState& fallback) {
  InterfaceSideState sum{0.0, 0.0, 0.0, 0.0};
  double w_sum = 0.0;
  const long cx = g.index(c.x()), cy = g.index(c.y()), cz = g.index(c.z());
  for (long ix = cx - 1; ix <= cx + 1; ++ix) {
    for (long iy = cy - 1; iy <= cy + 1; ++iy) {
      for (long iz = cz - 1; iz <= cz + 1; ++iz) {
        const auto it = g.cells.find(cell_key(ix, iy, iz));
        if (it == g.cells.end()) continue;
        for (const int j : it->second) {
          const MaterialSample& s = samples[j];
          const double w = s.weight * std::max(0.0, 1.0 - (s.x - c).norm() / length);
          if (!(w > 0.0)) continue;
          accumulate(sum, w, s.state);
          w_sum += w;
        }
      }
    }
  }
  if (!(w_sum > 0.0)) return fallback;
  return divided(sum, w_sum);
}

}  // namespace

InterfaceSideState side_state(const PointState& st, double T_melt) {
  InterfaceSideState s;
  s.yield_ratio = st.sigma_y_static_peak > 0.0 ? st.sigma_y_static / st.sigma_y_static_peak : 1.0;
  s.damage = st.D;
  s.flow_stress = st.sigma_y_static;
  s.homologous_temperature = T_melt > 0.0 ? st.T / T_melt : 0.0;
  return s;
}

void accumulate(InterfaceSideState& sum, double w, const InterfaceSideState& s) {
  sum.yield_ratio += w * s.yield_ratio;
  sum.damage += w * s.damage;
  sum.flow_stress += w * s.flow_stress;
  sum.homologous_temperature += w * s.homologous_temperature;
  sum.surface_expansion += w * s.surface_expansion;
}

InterfaceSideState divided(const InterfaceSideState& sum, double w_sum) {
  return {sum.yield_ratio / w_sum, sum.damage / w_sum, sum.flow_stress / w_sum,
          sum.homologous_temperature / w_sum, sum.surface_expansion / w_sum};
}

std::vector<InterfaceSideState> average_around(const std::vector<MaterialSample>& samples,
                                               const std::vector<Vec3>& centres, double length,
                                               const std::vector<InterfaceSideState>& fallback) {
  if (!(length > 0.0) || samples.empty()) return fallback;
  const CellGrid g = build_grid(samples, length);
  std::vector<InterfaceSideState> out(centres.size());
  for (std::size_t k = 0; k < centres.size(); ++k) {
    out[k] = average_one(samples, g, centres[k], length, fallback[k]);
  }
  return out;
}

}  // namespace splat
