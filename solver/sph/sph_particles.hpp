// Particle generation for SPH bodies: lattice points inside a sphere,
// cylinder or box, each with the volume of one lattice cell.
//
// Lattices at spacing d (nearest-neighbour distance):
//   cubic: points at (i + 1/2, j + 1/2, k + 1/2) d about the lattice origin;
//          cell volume d^3.
//   hcp:   hexagonal close packing, A-B stacking along z: triangular layers
//          (rows d apart along x, rows sqrt(3)/2 d apart along y), layer B
//          shifted by (d/2, d/(2 sqrt 3)), layers sqrt(2/3) d apart; cell
//          volume d^3 / sqrt(2).
// The lattice origin is the sphere's centre, the cylinder's axis point
// (0, 0, z_min) or the box's lower corner, offset so that no point lies on a
// symmetry plane x = 0 or y = 0 through it (cubic: points at d/2 from it).
// A box is filled exactly on the cubic lattice: n_k = max(1, round(L_k / d))
// points along each axis at spacing L_k / n_k, so the volumes add up to the
// box's. Round shapes keep the lattice points inside, so their total volume
// differs from the exact one by the lattice's surface roughness
// (ParticleCloud::volume_error reports it).
//
// Boundary layers: a particle within layers x d of a face of the primitive
// (and inside it) carries that face's BoundaryBit (solver/mesh/mesh.hpp):
// box faces x_min ... z_max; cylinder ends z_min, z_max and its side
// `curved`; sphere surface `curved`; the symmetry planes of half and quarter
// sectors x_min (x = 0) and y_min (y = 0).
//
// Optional jitter: each coordinate moves by a uniform random amount in
// [-jitter, +jitter] x d, reproducibly from the seed (off by default).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/common/types.hpp"

namespace splat {

enum class Lattice { cubic, hcp };
enum class ParticleShape { sphere, cylinder, box };
enum class ParticleSector { full, half, quarter };  // half: y >= 0; quarter: x, y >= 0

struct ParticleSpec {
  ParticleShape shape = ParticleShape::sphere;
  double radius = 0.0;                        // sphere and cylinder, m
  Vec3 centre = Vec3::Zero();                 // sphere, m
  double z_min = 0.0, z_max = 0.0;            // cylinder (axis z through x = y = 0), m
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // box corners, m
  ParticleSector sector = ParticleSector::full;
  Lattice lattice = Lattice::hcp;
  double spacing = 0.0;     // nearest-neighbour distance d, m
  int boundary_layers = 3;  // thickness of the tagged boundary layers, in spacings
  double jitter = 0.0;      // random displacement amplitude, fraction of d
  unsigned long long jitter_seed = 1;
};

struct ParticleCloud {
  std::vector<Vec3> x;                  // positions, m
  std::vector<double> volume;           // cell volumes, m^3
  std::vector<std::uint32_t> boundary;  // BoundaryBit mask
  std::vector<Vec3> outward_normal;     // unit outward normal of the curved surface at a
                                        //   `curved` particle (radial), else zero
  double spacing = 0.0;                 // d, m (for boxes: the mean of the three L_k / n_k)
  double layer_thickness = 0.0;         // boundary_layers x d, m
  double exact_volume = 0.0;            // of the (sector of the) primitive, m^3
  double volume_error = 0.0;            // sum of volumes / exact_volume - 1, -

  std::size_t size() const { return x.size(); }
};

// Throws std::invalid_argument for a non-positive spacing, radius or extent.
ParticleCloud generate_particles(const ParticleSpec& spec);

}  // namespace splat
