#include "solver/sph/sph_neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "solver/sph/sph_kernel.hpp"

namespace splat {

namespace {

void check_input(const std::vector<Vec3>& X, const std::vector<double>& h,
                 const SymmetryPlanes& planes, const std::vector<std::uint8_t>& active) {
  if (h.size() != X.size() || (!active.empty() && active.size() != X.size())) {
    throw std::invalid_argument("neighbour search: array sizes differ");
  }
  if (planes.size() > 3) throw std::invalid_argument("neighbour search: more than 3 planes");
  for (std::size_t a = 0; a < planes.size(); ++a) {
    if (planes[a].axis < 0 || planes[a].axis > 2) {
      throw std::invalid_argument("neighbour search: plane axis must be 0, 1 or 2");
    }
    for (std::size_t b = 0; b < a; ++b) {
      if (planes[a].axis == planes[b].axis) {
        throw std::invalid_argument("neighbour search: two symmetry planes on one axis");
      }
    }
  }
  for (double v : h) {
    if (!(v > 0.0)) throw std::invalid_argument("neighbour search: h must be > 0");
  }
}

bool is_active(const std::vector<std::uint8_t>& active, std::size_t i) {
  return active.empty() || active[i] != 0;
}

using Entry = std::pair<int, int>;  // (op, j), sorted

// Whether (i, j, op) is a pair, evaluated the same way for (j, i, op): the
// lower index is mirrored, so the lists are exactly symmetric in floating point.
bool within_support(const std::vector<Vec3>& X, const std::vector<double>& h,
                    const SymmetryPlanes& planes, std::uint8_t op, std::size_t i, std::size_t j) {
  const std::size_t a = std::min(i, j), b = std::max(i, j);
  const Vec3 d = op == 0 ? Vec3(X[a] - X[b]) : Vec3(mirror_point(planes, op, X[a]) - X[b]);
  const double support = kernel_support * 0.5 * (h[i] + h[j]);
  return d.squaredNorm() < support * support;
}

NeighbourList to_csr(std::vector<std::vector<Entry>>& lists) {
  NeighbourList out;
  out.offsets.assign(lists.size() + 1, 0);
  for (std::size_t i = 0; i < lists.size(); ++i) {
    std::sort(lists[i].begin(), lists[i].end());
    out.offsets[i + 1] = out.offsets[i] + static_cast<int>(lists[i].size());
  }
  out.j.reserve(static_cast<std::size_t>(out.offsets.back()));
  out.op.reserve(static_cast<std::size_t>(out.offsets.back()));
  for (const auto& list : lists) {
    for (const Entry& e : list) {
      out.op.push_back(static_cast<std::uint8_t>(e.first));
      out.j.push_back(e.second);
    }
  }
  return out;
}

}  // namespace

NeighbourList find_neighbours_all_pairs(const std::vector<Vec3>& X, const std::vector<double>& h,
                                        const SymmetryPlanes& planes,
                                        const std::vector<std::uint8_t>& active) {
  check_input(X, h, planes, active);
  const std::size_t n = X.size();
  const int num_ops = 1 << planes.size();
  std::vector<std::vector<Entry>> lists(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_active(active, i)) continue;
    for (int op = 0; op < num_ops; ++op) {
      for (std::size_t j = 0; j < n; ++j) {
        if (!is_active(active, j) || (op == 0 && i == j)) continue;
        if (within_support(X, h, planes, static_cast<std::uint8_t>(op), i, j)) {
          lists[i].emplace_back(op, static_cast<int>(j));
        }
      }
    }
  }
  return to_csr(lists);
}

NeighbourList find_neighbours(const std::vector<Vec3>& X, const std::vector<double>& h,
                              const SymmetryPlanes& planes,
                              const std::vector<std::uint8_t>& active) {
  check_input(X, h, planes, active);
  const std::size_t n = X.size();
  std::vector<std::vector<Entry>> lists(n);
  if (n == 0) return to_csr(lists);
  const double h_max = *std::max_element(h.begin(), h.end());
  // Cells at least 2 max h wide (no pair is farther apart than that), widened
  // when the particles are spread so thinly (a few that flew far away) that
  // the grid would hold many more cells than particles.
  double cell = kernel_support * h_max;
  Vec3 lo = X[0], hi = X[0];
  for (const Vec3& p : X) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!lo.allFinite() || !hi.allFinite()) {
    throw std::invalid_argument("neighbour search: non-finite position");
  }
  const double max_cells = 8.0 * static_cast<double>(n) + 64.0;
  long dims[3];
  for (;;) {
    double count = 1.0;
    for (int a = 0; a < 3; ++a) count *= std::floor((hi[a] - lo[a]) / cell) + 1.0;
    if (count <= max_cells) break;
    cell *= 2.0;
  }
  for (int a = 0; a < 3; ++a) {
    dims[a] = std::max(1L, static_cast<long>(std::floor((hi[a] - lo[a]) / cell)) + 1);
  }
  const auto cell_coord = [&](double v, int a) {
    return std::clamp(static_cast<long>(std::floor((v - lo[a]) / cell)), 0L, dims[a] - 1);
  };
  const auto cell_index = [&](long i, long j, long k) { return (k * dims[1] + j) * dims[0] + i; };

  // Counting sort of particles into cells (ascending particle index per cell).
  const std::size_t num_cells = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  std::vector<int> cell_start(num_cells + 1, 0);
  std::vector<long> cell_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell_of[i] =
        cell_index(cell_coord(X[i].x(), 0), cell_coord(X[i].y(), 1), cell_coord(X[i].z(), 2));
    ++cell_start[static_cast<std::size_t>(cell_of[i]) + 1];
  }
  for (std::size_t c = 0; c < num_cells; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<int> cell_items(n);
  {
    std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      cell_items[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[i])]++)] =
          static_cast<int>(i);
    }
  }

  const int num_ops = 1 << planes.size();
  const long long count = static_cast<long long>(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (long long ii = 0; ii < count; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    if (!is_active(active, i)) continue;
    std::vector<Entry>& list = lists[i];
    for (int op = 0; op < num_ops; ++op) {
      // |X_i - op X_j| = |op X_i - X_j|: search around the image of i (skipped
      // when it is more than a cell outside the particles' bounding box).
      const Vec3 q = mirror_point(planes, static_cast<std::uint8_t>(op), X[i]);
      long c0[3], c1[3];
      bool outside = false;
      for (int a = 0; a < 3; ++a) {
        const double f0 = std::floor((q[a] - cell - lo[a]) / cell);
        const double f1 = std::floor((q[a] + cell - lo[a]) / cell);
        if (f1 < 0.0 || f0 > static_cast<double>(dims[a] - 1)) outside = true;
        c0[a] = std::max(0L, static_cast<long>(f0));
        c1[a] = std::min(dims[a] - 1, static_cast<long>(f1));
      }
      if (outside) continue;
      for (long ck = c0[2]; ck <= c1[2]; ++ck)
        for (long cj = c0[1]; cj <= c1[1]; ++cj)
          for (long ci = c0[0]; ci <= c1[0]; ++ci) {
            const std::size_t c = static_cast<std::size_t>(cell_index(ci, cj, ck));
            for (int s = cell_start[c]; s < cell_start[c + 1]; ++s) {
              const std::size_t j =
                  static_cast<std::size_t>(cell_items[static_cast<std::size_t>(s)]);
              if (!is_active(active, j) || (op == 0 && i == j)) continue;
              if (within_support(X, h, planes, static_cast<std::uint8_t>(op), i, j)) {
                list.emplace_back(op, static_cast<int>(j));
              }
            }
          }
    }
  }
  return to_csr(lists);
}

}  // namespace splat
