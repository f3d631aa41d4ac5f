// Meshes produced by the generators in solver/mesh/ and consumed by the finite
// element bodies. Pure geometry and topology; no physics state.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/common/types.hpp"

namespace splat {

// Which boundary of the generating primitive a node or face lies on. A node on
// an edge or corner carries several bits.
enum BoundaryBit : std::uint32_t {
  boundary_none = 0,
  boundary_x_min = 1u << 0,  // axisymmetric: r = 0, the symmetry axis
  boundary_x_max = 1u << 1,  // axisymmetric: r = r_max, the outer radius
  boundary_y_min = 1u << 2,  // axisymmetric: z = z_min (bottom)
  boundary_y_max = 1u << 3,  // axisymmetric: z = z_max (top)
  boundary_z_min = 1u << 4,
  boundary_z_max = 1u << 5,
  boundary_curved = 1u << 6,  // the curved surface of a sphere or cylinder
};

// Axisymmetric mesh in the (r, z) half-plane, r >= 0. Quads are numbered
// counter-clockwise in (r, z) so that their signed area is positive.
struct AxisymMesh {
  std::vector<Vec2> nodes;                            // (r, z), m
  std::vector<std::array<int, 4>> quads;              // node indices, counter-clockwise
  std::vector<std::uint32_t> node_boundary;           // BoundaryBit mask per node
  std::vector<std::array<int, 2>> boundary_segments;  // outward normal on the right of a->b
  std::vector<std::uint32_t> segment_boundary;        // BoundaryBit per segment
};

// Faces of the unit-cube hexahedron (HexMesh node order) by local node,
// counter-clockwise seen from outside.
inline constexpr std::array<std::array<int, 4>, 6> k_hex_faces{{
    {0, 3, 2, 1},  // z = 0
    {4, 5, 6, 7},  // z = 1
    {0, 1, 5, 4},  // y = 0
    {2, 3, 7, 6},  // y = 1
    {3, 0, 4, 7},  // x = 0
    {1, 2, 6, 5},  // x = 1
}};

// 3D hexahedral mesh. Node order per hexahedron is that of the unit cube
// 0=(0,0,0) 1=(1,0,0) 2=(1,1,0) 3=(0,1,0) 4=(0,0,1) 5=(1,0,1) 6=(1,1,1)
// 7=(0,1,1) mapped into place, so the signed volume is positive.
struct HexMesh {
  std::vector<Vec3> nodes;                         // m
  std::vector<std::array<int, 8>> hexes;           // node indices, positive volume
  std::vector<std::uint32_t> node_boundary;        // BoundaryBit mask per node
  std::vector<std::array<int, 4>> boundary_faces;  // counter-clockwise seen from outside
  std::vector<std::uint32_t> face_boundary;        // BoundaryBit per face
};

}  // namespace splat
