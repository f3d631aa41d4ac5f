// Contact surfaces and detection: which master face each slave node is over.
//
// Detection kinds (one contact/adhesion interface, several kinds; SPH pinball
// and SPH-on-FE pairs come later):
//   node_on_segment  axisymmetric FE: slave nodes on master boundary segments
//   node_on_quad     3D hexahedral FE: slave nodes on master boundary quads
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

#include <array>
#include <cstdint>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/contact/contact_geometry.hpp"

namespace splat {

enum class DetectionKind { node_on_segment, node_on_quad };

// Faces of one body that take part in contact (set once; global node ids).
struct ContactSurface {
  DetectionKind kind = DetectionKind::node_on_segment;
  std::vector<std::array<int, 4>> faces;  // segments use the first 2 ids
  // Slave side: the distinct nodes of `faces`, ascending, and for each the
  // faces it belongs to (CSR), for its tributary area.
  std::vector<int> nodes;
  std::vector<int> node_face_offsets;
  std::vector<int> node_face_entries;

  int nodes_per_face() const { return kind == DetectionKind::node_on_segment ? 2 : 4; }
};

// Builds the node lists of a surface from its faces.
ContactSurface make_contact_surface(DetectionKind kind, std::vector<std::array<int, 4>> faces);

// Tributary area of slave node `k` (index into surface.nodes) on the current
// positions x: axisymmetric, r times half the lengths of its segments (per
// radian; 2 pi times this is the ring area of thesis 2.2.4 extended to FE);
// 3D, a quarter of the area of each of its faces. m^2 (per radian in 2D).
double slave_node_area(const ContactSurface& s, int k, const std::vector<Vec3>& x);

// Size of master face f on x: segment length or sqrt(area), m.
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
};

// Pairs sorted by slave index; at most one per slave node.
std::vector<DetectedPair> find_pairs_buckets(const ContactSurface& master,
                                             const ContactSurface& slave,
                                             const std::vector<Vec3>& x,
                                             const SearchSettings& settings);
std::vector<DetectedPair> find_pairs_all_pairs(const ContactSurface& master,
                                               const ContactSurface& slave,
                                               const std::vector<Vec3>& x,
                                               const SearchSettings& settings);

}  // namespace splat
