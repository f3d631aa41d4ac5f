// Pointwise geometry of one contact pair: a slave point against a master
// segment (axisymmetric, in the (r, z) plane) or a master bilinear quad face
// (3D). Pure functions of the coordinates; no state.
//
// The gap is the signed distance of the slave point from the master surface
// along the master's outward normal n (positive outside, negative when the
// point has penetrated). The constraint row of the pair (thesis eq. 1.22,
// C of F = C^T lambda) has +n on the slave node and -w_k n on master node k,
// with w_k the master shape functions at the projection, so a positive
// multiplier pushes the slave out along n and the master in, with equal and
// opposite total force.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/common/types.hpp"

namespace splat {

struct PairGeometry {
  double gap = 0.0;                 // m, signed, along `normal`
  Vec3 normal = Vec3::UnitZ();      // master outward unit normal at the projection
  Vec3 tangent1 = Vec3::UnitX();    // unit, in the master surface
  Vec3 tangent2 = Vec3::Zero();     // unit, in the master surface (3D), zero in 2D
  std::array<double, 4> weights{};  // master shape functions at the projection
  double xi = 0.0, eta = 0.0;       // local coordinates of the projection
  double distance_outside = 0.0;    // how far the projection is outside the face, in
                                    //   local coordinates (0 inside)
  bool valid = false;               // false for a degenerate face
};

// Segment a -> b in the (r, z) plane (components 0, 1); its outward normal is
// on the right of a -> b (mesh.hpp). xi in [0, 1] along the segment;
// weights = (1 - xi, xi). The projection is clamped to the segment for the
// weights; distance_outside says by how much (in units of the length) xi was
// outside [0, 1].
inline PairGeometry project_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  PairGeometry g;
  const Vec3 d = b - a;
  const double len_sq = d.squaredNorm();
  if (!(len_sq > 0.0)) return g;
  const double len = std::sqrt(len_sq);
  g.valid = true;
  g.normal = Vec3(d.y(), -d.x(), 0.0) / len;
  g.tangent1 = d / len;
  g.tangent2 = Vec3::Zero();
  const double xi = (p - a).dot(d) / len_sq;
  g.distance_outside = xi < 0.0 ? -xi : (xi > 1.0 ? xi - 1.0 : 0.0);
  g.xi = std::clamp(xi, 0.0, 1.0);
  g.weights = {1.0 - g.xi, g.xi, 0.0, 0.0};
  g.gap = (p - a).dot(g.normal);
  return g;
}

// Bilinear quad x0..x3, counter-clockwise seen from outside (mesh.hpp), local
// coordinates (xi, eta) in [-1, 1]^2 with node k at (xi_k, eta_k) =
// (-1,-1), (1,-1), (1,1), (-1,1). Closest-point projection by Newton's method
// on (x(xi, eta) - p) . x_xi = (x(xi, eta) - p) . x_eta = 0 (exact Hessian of
// the bilinear map, a few iterations from the centre); the normal is
// x_xi x x_eta normalised at the projection. The local coordinates are
// clamped to the face for the weights; distance_outside is how far (in local
// units, a face spans 2) the unclamped projection lay outside.
inline PairGeometry project_on_quad(const Vec3& p, const std::array<Vec3, 4>& x) {
  PairGeometry g;
  static constexpr double xs[4] = {-1.0, 1.0, 1.0, -1.0};
  static constexpr double es[4] = {-1.0, -1.0, 1.0, 1.0};
  // x(xi, eta) = c0 + c1 xi + c2 eta + c3 xi eta
  const Vec3 c0 = 0.25 * (x[0] + x[1] + x[2] + x[3]);
  const Vec3 c1 = 0.25 * (-x[0] + x[1] + x[2] - x[3]);
  const Vec3 c2 = 0.25 * (-x[0] - x[1] + x[2] + x[3]);
  const Vec3 c3 = 0.25 * (x[0] - x[1] + x[2] - x[3]);
  if (!(c1.cross(c2).squaredNorm() > 0.0)) return g;
  double xi = 0.0, eta = 0.0;
  for (int it = 0; it < 12; ++it) {
    const Vec3 r = c0 + c1 * xi + c2 * eta + c3 * (xi * eta) - p;
    const Vec3 tx = c1 + c3 * eta;
    const Vec3 te = c2 + c3 * xi;
    const double f0 = r.dot(tx), f1 = r.dot(te);
    const double j00 = tx.dot(tx), j11 = te.dot(te), j01 = tx.dot(te) + r.dot(c3);
    const double det = j00 * j11 - j01 * j01;
    if (!(std::abs(det) > 0.0)) break;
    const double dxi = (j11 * f0 - j01 * f1) / det;
    const double deta = (j00 * f1 - j01 * f0) / det;
    xi -= dxi;
    eta -= deta;
    // Far outside the face the exact projection is irrelevant: stop early.
    xi = std::clamp(xi, -3.0, 3.0);
    eta = std::clamp(eta, -3.0, 3.0);
    if (std::abs(dxi) + std::abs(deta) < 1e-12) break;
  }
  const double oxi = std::max(std::abs(xi) - 1.0, 0.0);
  const double oeta = std::max(std::abs(eta) - 1.0, 0.0);
  g.distance_outside = std::max(oxi, oeta);
  xi = std::clamp(xi, -1.0, 1.0);
  eta = std::clamp(eta, -1.0, 1.0);
  g.xi = xi;
  g.eta = eta;
  for (int k = 0; k < 4; ++k) g.weights[k] = 0.25 * (1.0 + xs[k] * xi) * (1.0 + es[k] * eta);
  const Vec3 tx = c1 + c3 * eta;
  const Vec3 te = c2 + c3 * xi;
  const Vec3 nv = tx.cross(te);
  const double nn = nv.norm();
  if (!(nn > 0.0)) return g;
  g.valid = true;
  g.normal = nv / nn;
  g.tangent1 = tx.normalized();
  g.tangent2 = g.normal.cross(g.tangent1);
  const Vec3 xp = c0 + c1 * xi + c2 * eta + c3 * (xi * eta);
  g.gap = (p - xp).dot(g.normal);
  return g;
}

// Area of a quad face (exact for a planar one; the norm of half the diagonal
// cross product), m^2.
inline double quad_area(const std::array<Vec3, 4>& x) {
  return 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm();
}

}  // namespace splat
