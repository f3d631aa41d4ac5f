// SPH bodies in the Simulation's model: builds a body's particles from its
// BodySpec (particle spacing from the discretization's element_size or
// elements_across), its mirrored-ghost symmetry planes from the scene's
// symmetry conditions, and its absorbing layers. Used by model_builder.cpp.
#pragma once

#include <cstdint>

#include "solver/scene/scene.hpp"
#include "solver/sph/sph_body.hpp"
#include "solver/sph/sph_boundary.hpp"

namespace splat {

// Particle spacing of an sph body, m: element_size, or the characteristic
// length (radius of spheres and cylinders, smallest side of boxes) over
// elements_across.
double sph_spacing(const BodySpec& b);

// Symmetry planes of scene body `index`: one per symmetry condition on it
// (x_min, y_min, ... at the geometry's bound on that side: the cut plane
// x = centre.x / y = centre.y of half and quarter spheres and cylinders).
// Throws InputError naming the condition when it has no plane.
SymmetryPlanes sph_symmetry_planes(const Scene& scene, std::size_t index);

// Generates the particles of scene body `index` and appends them to `nodes`.
// Throws InputError naming the body's field on bad settings.
SphBody build_sph_body(const Scene& scene, std::size_t index, NodeSet& nodes);

// Absorbing layer on the faces `on` of an sph body built from `spec`.
SphAbsorbing build_sph_absorbing(const BodySpec& spec, const SphBody& body, const NodeSet& nodes,
                                 std::uint32_t on);

}  // namespace splat
