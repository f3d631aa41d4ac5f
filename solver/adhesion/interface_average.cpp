#include "solver/adhesion/interface_average.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace splat {
namespace {

using CellKey = std::int64_t;

// Cell of side l holding x; 21 bits per axis cover +-1e6 cells.
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

CellGrid build_grid(const std::vector<InterfaceSample>& samples, double length) {
  CellGrid g;
  g.size = length;
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const Vec3& x = samples[j].x;
    g.cells[cell_key(g.index(x.x()), g.index(x.y()), g.index(x.z()))].push_back(
        static_cast<int>(j));
  }
  return g;
}

void accumulate(InterfaceAverage& sum, const InterfaceSample& s, double w) {
  sum.slave.yield_ratio += w * s.slave.yield_ratio;
  sum.slave.damage += w * s.slave.damage;
  sum.slave.flow_stress += w * s.slave.flow_stress;
  sum.master.flow_stress += w * s.master.flow_stress;
  sum.master.yield_ratio += w * s.master.yield_ratio;
  sum.master.damage += w * s.master.damage;
}

InterfaceAverage average_one(const std::vector<InterfaceSample>& samples, const CellGrid& g,
                             std::size_t k, double length) {
  const InterfaceSample& me = samples[k];
  InterfaceAverage sum{{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  double w_sum = 0.0;
  const long cx = g.index(me.x.x()), cy = g.index(me.x.y()), cz = g.index(me.x.z());
  for (long ix = cx - 1; ix <= cx + 1; ++ix) {
    for (long iy = cy - 1; iy <= cy + 1; ++iy) {
      for (long iz = cz - 1; iz <= cz + 1; ++iz) {
        const auto it = g.cells.find(cell_key(ix, iy, iz));
        if (it == g.cells.end()) continue;
        for (const int j : it->second) {
          const double r = (samples[j].x - me.x).norm();
          const double w = samples[j].area * std::max(0.0, 1.0 - r / length);
          if (!(w > 0.0)) continue;
          accumulate(sum, samples[j], w);
          w_sum += w;
        }
      }
    }
  }
  if (!(w_sum > 0.0)) return {me.slave, me.master};
  const double inv = 1.0 / w_sum;
  return {{sum.slave.yield_ratio * inv, sum.slave.damage * inv, sum.slave.flow_stress * inv},
          {sum.master.yield_ratio * inv, sum.master.damage * inv, sum.master.flow_stress * inv}};
}

}  // namespace

std::vector<InterfaceAverage> average_interface(const std::vector<InterfaceSample>& samples,
                                                double length) {
  std::vector<InterfaceAverage> out(samples.size());
  if (!(length > 0.0)) {
    for (std::size_t k = 0; k < samples.size(); ++k) out[k] = {samples[k].slave, samples[k].master};
    return out;
  }
  const CellGrid g = build_grid(samples, length);
  for (std::size_t k = 0; k < samples.size(); ++k) out[k] = average_one(samples, g, k, length);
  return out;
}

}  // namespace splat
