// Neighbour lists of SPH particles in their reference configuration, with
// mirrored ghosts across symmetry planes.
//
// Particles i and j are neighbours when |X_i - X_j| < 2 h_ij with
// h_ij = (h_i + h_j) / 2 (both kernels reach 2h), i != j. Across symmetry
// planes, particle i also sees the mirror image op(X_j) of every particle j
// (itself included) with |X_i - op(X_j)| < 2 h_ij, where op is a non-empty set
// of planes (a bitmask over SymmetryPlanes, the reflections applied one after
// the other; they commute since each plane is normal to a different axis).
// Each op is its own inverse and an isometry, so |X_i - op X_j| =
// |op X_i - X_j|: the lists are symmetric, (i, j, op) present iff (j, i, op).
//
// find_neighbours uses a cell search (cells 2 max h wide; 27 cells around X_i
// or around op(X_i)); find_neighbours_all_pairs is the slow obvious check.
// Both give each particle's list sorted by (op, j).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/common/types.hpp"

namespace splat {

// The plane X[axis] = position, normal to a coordinate axis.
struct SymmetryPlane {
  int axis = 0;           // 0, 1, 2 for x, y, z
  double position = 0.0;  // m
};

// At most one plane per axis.
using SymmetryPlanes = std::vector<SymmetryPlane>;

// Mirror of a point across the planes in `op`.
inline Vec3 mirror_point(const SymmetryPlanes& planes, std::uint8_t op, Vec3 p) {
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (op & (1u << k)) p[planes[k].axis] = 2.0 * planes[k].position - p[planes[k].axis];
  }
  return p;
}

// Mirror of a vector (velocity, force) across the planes in `op`.
inline Vec3 mirror_vector(const SymmetryPlanes& planes, std::uint8_t op, Vec3 v) {
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (op & (1u << k)) v[planes[k].axis] = -v[planes[k].axis];
  }
  return v;
}

// S A S of a tensor A, S the reflection of `op`.
inline Mat3 mirror_tensor(const SymmetryPlanes& planes, std::uint8_t op, Mat3 A) {
  for (std::size_t k = 0; k < planes.size(); ++k) {
    if (op & (1u << k)) {
      const int a = planes[k].axis;
      A.row(a) *= -1.0;
      A.col(a) *= -1.0;
    }
  }
  return A;
}

// CSR neighbour lists: the neighbours of i are entries offsets[i] ..
// offsets[i + 1] - 1 of j and op (op = 0: the particle itself, else its mirror).
struct NeighbourList {
  std::vector<int> offsets;
  std::vector<int> j;
  std::vector<std::uint8_t> op;

  std::size_t num_particles() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t num_pairs() const { return j.size(); }
};

// `active` (empty = all) excludes particles from every list, theirs included.
// Throws std::invalid_argument for more than 3 planes, two on one axis, or a
// non-positive h.
NeighbourList find_neighbours(const std::vector<Vec3>& X, const std::vector<double>& h,
                              const SymmetryPlanes& planes,
                              const std::vector<std::uint8_t>& active = {});
NeighbourList find_neighbours_all_pairs(const std::vector<Vec3>& X, const std::vector<double>& h,
                                        const SymmetryPlanes& planes,
                                        const std::vector<std::uint8_t>& active = {});

}  // namespace splat
