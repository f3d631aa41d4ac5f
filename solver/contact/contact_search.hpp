// Contact surfaces and detection: which master face each slave node is over.
//
// Detection kinds (one contact/adhesion interface, several kinds):
//   node_on_segment  axisymmetric FE: slave nodes on master boundary segments
//   node_on_quad     3D hexahedral FE: slave nodes on master boundary quads
//   particle_pinball SPH: each "face" is one particle (a pinball of radius R,
//                    half the particle spacing); a slave point p pairs with
//                    the master particle m with gap |p - x_m| - R_m, normal
//                    (p - x_m) / |p - x_m|, weight 1 on m. A master particle
//                    on its body's surface (outward normal n_m) is a cap
//                    instead, for p outside its tangent plane (d . n_m > 0,
//                    d = p - x_m): a sphere of radius R_c = k_cap_curvature
//                    R_m through the pinball's top, centred at c = x_m -
//                    (R_c - R_m) n_m, gap |p - c| - R_c, normal (p - c) /
//                    |p - c| (the gap's gradient, as the Lagrange rows
//                    assume). A particle sliding over a layer of
//                    pinballs drops into the hollows between them and lands
//                    in each (a node-level plastic impact): an Al/Al impact
//                    without adhesion at 600 m/s stays in its crater at 6
//                    spacings across, flattens to 1.30 where FE gives 1.54,
//                    and its surface particles, kicked by the bumps, book
//                    6-18 % of the impact energy more plastic work than the
//                    material stored (docs/verification.md). The caps' bumps
//                    are less than half as high.
// A slave surface may give each node a radius (SPH particles as slaves, on
// pinball or quad masters): the gap is then measured from the slave's
// pinball surface, gap - R_s. So SPH-SPH pairs touch at |x_s - x_m| = R_s +
// R_m, and an SPH particle touches an FE face at distance R_s. On an FE face
// a slave particle pairs with one face (the best, as FE nodes); on pinball
// masters with every master particle in range (one pair per slave lets it
// slide along one pair's normal into the next pinball, and the next step's
// correction of that penetration, gap / dt, kicks it: at 600 m/s this blew
// up an Al/Al impact).
//
// A slave node pairs with the master face that contains its projection
// (within a small tolerance) and is nearest along the normal, provided its gap
// lies in [-capture_depth, search_margin] (both as fractions of the face's
// size: its length, or the square root of its area). The bucket search puts
// each face into the cells of a uniform grid that its bounding box, grown by
// its capture range, overlaps; a slave node then only tests the faces of its
// own cell. find_pairs_all_pairs tests every face and must give identical
// pairs (unit test).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/contact/contact_geometry.hpp"

namespace splat {

enum class DetectionKind { node_on_segment, node_on_quad, particle_pinball };

// Faces of one body that take part in contact (set once; global node ids).
struct ContactSurface {
  DetectionKind kind = DetectionKind::node_on_segment;
  std::vector<std::array<int, 4>> faces;  // segments use the first 2 ids
  // Slave side: the distinct nodes of `faces`, ascending, and for each the
  // faces it belongs to (CSR), for its tributary area.
  std::vector<int> nodes;
  std::vector<int> node_face_offsets;
  std::vector<int> node_face_entries;
  // Pinball radius of each node (same order as `nodes`), m; empty for FE
  // surfaces (radius 0). Required for particle_pinball surfaces.
  std::vector<double> radius;
  // Deformed pinballs (SPH bodies; set every step by the contact interface):
  // each particle's inverse deformation gradient from its initial state, and
  // the largest radius its pinball reaches, m. Empty: spheres of `radius`.
  std::vector<Mat3> inverse_stretch;
  std::vector<double> reach;
  // Caps (SPH masters; set every step by the contact interface): the outward
  // unit normal of each particle on the body's surface, zero inside. Empty:
  // every particle is a pinball.
  std::vector<Vec3> cap_normal;

  int nodes_per_face() const {
    switch (kind) {
      case DetectionKind::node_on_segment:
        return 2;
      case DetectionKind::node_on_quad:
        return 4;
      case DetectionKind::particle_pinball:
        return 1;
    }
    return 4;
  }
  double node_radius(int k) const { return radius.empty() ? 0.0 : radius[k]; }
  double node_reach(int k) const { return reach.empty() ? node_radius(k) : reach[k]; }
  // Radius of node k's pinball along the unit vector n, m. A deformed
  // particle's pinball is its initial ball mapped by F, an ellipsoid of
  // radius R / |F^-1 n| along n, but never smaller than R: where a surface
  // layer is stretched its particles part, and only their stretched extent
  // keeps the other body out of the gaps; where it is compressed, R is the
  // distance the physics guard holds the bodies to.
  double radius_along(int k, const Vec3& n) const {
    const double r = node_radius(k);
    if (inverse_stretch.empty()) return r;
    return std::clamp(r / (inverse_stretch[k] * n).norm(), r, reach[k]);
  }
};

// A particle deformed less than this (||F - I||, Frobenius) keeps its
// spherical pinball: its radius along any direction is then within this
// fraction of R, -.
inline constexpr double k_round_pinball_deformation = 0.01;
// Curvature radius of a surface particle's cap over its pinball radius R, -:
// 4 R is two particle spacings, the support radius 2 h of the cubic-spline
// kernel at h = d, below which the particles do not resolve their surface.
// Between the particles of a square surface layer, a point 2 R above it sees
// bumps of 0.20 R on caps against 0.45 R on pinballs.
inline constexpr double k_cap_curvature = 4.0;
// Largest pinball radius over R, -: bounds the search range.
inline constexpr double k_max_pinball_stretch = 3.0;

// Gives pinball k of a particle_pinball surface the shape of its particle's
// deformation gradient F (from the initial state): inverse_stretch F^-1 and
// reach R times the largest principal stretch sigma_max(F) (the exact
// largest radius of the ellipsoid, so a rotation leaves the reach at R),
// clamped to [R, k_max_pinball_stretch R]. A nearly undeformed, inverted or
// non-finite F leaves the pinball a sphere of radius R. Sizes the shape
// arrays on first use.
void set_pinball_shape(ContactSurface& s, int k, const Mat3& F);

// Builds the node lists of a surface from its faces.
ContactSurface make_contact_surface(DetectionKind kind, std::vector<std::array<int, 4>> faces);
// A particle_pinball surface of the given particles (global ids) and radii (m).
ContactSurface make_particle_surface(const std::vector<int>& particles,
                                     const std::vector<double>& radius);

// Tributary area of slave node `k` (index into surface.nodes) on the current
// positions x: axisymmetric, r times half the lengths of its segments (per
// radian; 2 pi times this is the ring area of thesis 2.2.4 extended to FE);
// 3D, a quarter of the area of each of its faces; a particle, pi R^2 (thesis
// 2.2.4). m^2 (per radian in 2D).
double slave_node_area(const ContactSurface& s, int k, const std::vector<Vec3>& x);

// Area of face f of an FE surface on positions x: a quad's area (3D), or a
// segment's length times its mean radius (axisymmetric, per radian: the
// ring it sweeps over 2 pi), m^2.
double face_area(const ContactSurface& s, int f, const std::vector<Vec3>& x);

// Surface expansion of Bay's cold-welding model, Y = (A - A0) / A, on the
// reference positions x0 and the current x: of face f (face_area), and of
// slave node k over the faces it belongs to (their areas summed, so a node
// on the axis of an axisymmetric surface has one). 0 for an unstretched or a
// compressed surface (A <= A0) and for a degenerate one, -.
double face_surface_expansion(const ContactSurface& s, int f, const std::vector<Vec3>& x0,
                              const std::vector<Vec3>& x);
double node_surface_expansion(const ContactSurface& s, int k, const std::vector<Vec3>& x0,
                              const std::vector<Vec3>& x);

// Size of master face f on x: segment length, sqrt(area), or a particle's
// largest diameter 2 reach, m.
double face_size(const ContactSurface& s, int f, const std::vector<Vec3>& x);

struct SearchSettings {
  double capture_depth = 0.5;       // deepest gap accepted, fraction of the face size, -
  double search_margin = 0.1;       // largest gap accepted, fraction of the face size, -
  double outside_tolerance = 0.05;  // projection outside the face accepted, local units, -
};

struct DetectedPair {
  int slave = 0;  // index into the slave surface's nodes
  int face = 0;   // index into the master surface's faces
  PairGeometry geometry;
  // The slave's first (smallest-gap) pair; only pinball masters give a slave
  // further pairs, which carry compression only (adhesion acts on the
  // primary pair).
  bool primary = true;
};

// Slave node k against master face f alone, accepting gaps up to max_gap
// (m) instead of the search margin (the other tests of the search hold):
// the pair of a bonded node whose pair has opened past the margin; empty if
// the node does not project onto the face or lies outside the gap range.
std::optional<DetectedPair> pair_on_face(const ContactSurface& master, int f,
                                         const ContactSurface& slave, int k,
                                         const std::vector<Vec3>& x, const SearchSettings& st,
                                         double max_gap);

// Pairs sorted by slave index; at most one per slave node, except on
// particle_pinball masters: every master particle in range (a slave particle
// sits in the hollow between several), sorted by gap, the first primary.
std::vector<DetectedPair> find_pairs_buckets(const ContactSurface& master,
                                             const ContactSurface& slave,
                                             const std::vector<Vec3>& x,
                                             const SearchSettings& settings);
std::vector<DetectedPair> find_pairs_all_pairs(const ContactSurface& master,
                                               const ContactSurface& slave,
                                               const std::vector<Vec3>& x,
                                               const SearchSettings& settings);

}  // namespace splat
