// Structured, block-built mesh generators for the bodies of a cold-spray impact:
// a spherical particle, a substrate block and a Taylor anvil cylinder, as 2D
// axisymmetric quads in (r, z) or as 3D hexahedra. All lengths in m; the
// generators are scale-free.
//
// Round shapes use an O-grid: a core block (a square or cube lattice, slightly
// rounded towards the inscribed disc or ball) surrounded by one shell block per
// core face, whose radial lines run straight from the core's boundary nodes to
// equiangular (tan-spaced) nodes on the circle or sphere. Surface nodes lie on
// it to rounding, nodes on an axis or symmetry plane have that coordinate
// exactly zero, and no cell is collapsed or triangle-like, the axis included.
// With n elements along a radius the core spans round(0.6 n) of them.
//
// Every node has one position computed from a block-independent lattice key,
// so nodes shared by blocks are created once (no merging tolerance needed).
// Boundary tags follow mesh.hpp: a boundary face (segment) is one whose nodes
// all carry a common BoundaryBit, and it carries exactly that bit.
#pragma once

#include <vector>

#include "solver/common/types.hpp"
#include "solver/mesh/mesh.hpp"

namespace splat {

// Element size grows geometrically away from `focus` by `ratio` per element
// along each axis separately (ratio >= 1; 1 = uniform). For 2D meshes the
// focus is (r, z) = (focus.x, focus.y). Within `uniform_extent` of the focus
// along an axis the elements keep the base size; the growth starts beyond.
// Ignored unless `enabled`.
struct Grading {
  bool enabled = false;
  Vec3 focus = Vec3::Zero();  // m
  double ratio = 1.0;         // size of an element / size of its neighbour nearer the focus, -
  Vec3 uniform_extent = Vec3::Zero();  // m, half-widths of the uniform zone per axis
};

// n + 1 points from a to b (both exact). Element sizes grow by `ratio` per
// element away from `focus`, which is clamped to [a, b]. A focus strictly
// inside becomes a node with sizes growing both ways; the split n = n_left +
// n_right is the one whose two smallest sizes are closest, so only the two
// elements next to the focus may differ by more than `ratio` (by at most
// ~2 ratio + 1). A focus closer to an end than half the smallest one-sided
// element snaps to that end, so it never creates a sliver.
std::vector<double> graded_points(double a, double b, int n, double focus, double ratio);

// Points from a to b (both exact) for elements of about size h at the focus:
// uniform (size h, to rounding) within `uniform` of the focus, then growing
// by `ratio` per element, the first grown element at most h. With `uniform`
// 0 this is graded_points with the count that makes the element at the focus
// about h. An outer part shorter than h / 2 joins the uniform zone, so no
// sliver is made at its end.
std::vector<double> axis_points(double a, double b, double h, double focus, double ratio,
                                double uniform);

// Axisymmetric sphere: the half-disc r >= 0 of radius `radius` about
// (0, z_centre). Tags: axis r = 0 boundary_x_min, arc boundary_curved.
AxisymMesh axisym_half_disc(double radius, double z_centre, int elements_across_radius);

// Substrate block or cylinder [0, r_max] x [z_min, z_max] with n_r x n_z cells.
// Tags: r = 0 x_min (axis), r = r_max x_max, z_min y_min, z_max y_max.
AxisymMesh axisym_rectangle(double r_max, double z_min, double z_max, int n_r, int n_z,
                            const Grading& grading);
// The same block on given node lines: r from 0 to r_max, z increasing.
AxisymMesh axisym_rectangle(const std::vector<double>& r, const std::vector<double>& z);

// Part of a round body kept, relative to its centre (axis).
enum class Sector {
  full,
  half,     // y >= 0; the plane y = 0 is tagged boundary_y_min
  quarter,  // x >= 0 and y >= 0; planes x = 0 and y = 0 tagged x_min and y_min
};

// Cubed sphere (3D O-grid): a cube core blended into a six-block spherical
// shell. Surface tagged boundary_curved.
HexMesh hex_sphere(double radius, Vec3 centre, int elements_across_radius, Sector sector);

// Box [lo, hi] with nx x ny x nz cells. Faces tagged x_min ... z_max.
HexMesh hex_box(Vec3 lo, Vec3 hi, int nx, int ny, int nz, const Grading& grading);
// The same box on given node planes, each list increasing.
HexMesh hex_box(const std::vector<double>& x, const std::vector<double>& y,
                const std::vector<double>& z);

// Cylinder of `radius` along z through x = y = 0 from z_min to z_max: a 2D
// O-grid section (square core + four blended blocks) extruded in n_z layers,
// graded along z by axial.focus.z. Tags: mantle curved, ends z_min / z_max.
HexMesh hex_cylinder(double radius, double z_min, double z_max, int elements_across_radius, int n_z,
                     Sector sector, const Grading& axial);

}  // namespace splat
