#include "solver/core/sph_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "solver/input/schema.hpp"
#include "solver/mesh/mesh.hpp"
#include "solver/sph/sph_particles.hpp"

namespace splat {

namespace {

[[noreturn]] void fail(const std::string& pointer, const std::string& message) {
  throw InputError({SchemaViolation{pointer, message}});
}

std::string body_pointer(std::size_t b) {
  return "/bodies/" + std::to_string(b);
}

double characteristic_length(const Geometry& g) {
  switch (g.type) {
    case GeometryType::box:
      return (g.hi - g.lo).minCoeff();
    case GeometryType::sphere:
    case GeometryType::cylinder:
    case GeometryType::half_disc:
    case GeometryType::rectangle:
      break;
  }
  return g.radius;
}

ParticleSector to_particle_sector(SectorKind s) {
  switch (s) {
    case SectorKind::full:
      return ParticleSector::full;
    case SectorKind::half:
      return ParticleSector::half;
    case SectorKind::quarter:
      return ParticleSector::quarter;
  }
  return ParticleSector::full;
}

}  // namespace

double sph_spacing(const BodySpec& b) {
  if (b.element_size > 0.0) return b.element_size;
  return characteristic_length(b.geometry) / std::max(1, b.elements_across);
}

SymmetryPlanes sph_symmetry_planes(const Scene& scene, std::size_t index) {
  const BodySpec& b = scene.bodies[index];
  const Geometry& g = b.geometry;
  SymmetryPlanes planes;
  for (std::size_t ci = 0; ci < scene.boundaries.size(); ++ci) {
    const BoundarySpec& bc = scene.boundaries[ci];
    if (bc.type != BoundaryType::symmetry || bc.body != b.name) continue;
    const std::string ptr = "/boundary_conditions/" + std::to_string(ci) + "/on";
    struct Side {
      std::uint32_t bit;
      int axis;
      bool max;
    };
    const Side sides[] = {{boundary_x_min, 0, false}, {boundary_x_max, 0, true},
                          {boundary_y_min, 1, false}, {boundary_y_max, 1, true},
                          {boundary_z_min, 2, false}, {boundary_z_max, 2, true}};
    bool found = false;
    for (const Side& s : sides) {
      if (!(bc.on & s.bit)) continue;
      found = true;
      double position = 0.0;
      if (g.type == GeometryType::box) {
        position = s.max ? g.hi[s.axis] : g.lo[s.axis];
      } else if (s.axis < 2 && !s.max && b.sector != SectorKind::full &&
                 (s.axis == 1 || b.sector == SectorKind::quarter)) {
        // The cut plane of a half (y) or quarter (x and y) sector.
        position = g.type == GeometryType::sphere ? g.centre[s.axis] : 0.0;
      } else if (g.type == GeometryType::cylinder && s.axis == 2) {
        position = s.max ? g.z_max : g.z_min;
      } else {
        fail(ptr,
             "an sph symmetry plane must be a box face, a cylinder end or the cut plane of a "
             "half or quarter sector");
      }
      for (const SymmetryPlane& p : planes) {
        if (p.axis == s.axis) fail(ptr, "at most one symmetry plane per axis on an sph body");
      }
      planes.push_back({s.axis, position});
    }
    if (!found) fail(ptr, "a symmetry condition needs a plane (x_min ... z_max)");
  }
  return planes;
}

SphBody build_sph_body(const Scene& scene, std::size_t index, NodeSet& nodes) {
  const BodySpec& b = scene.bodies[index];
  const std::string ptr = body_pointer(index);
  const Geometry& g = b.geometry;
  ParticleSpec spec;
  switch (g.type) {
    case GeometryType::sphere:
      spec.shape = ParticleShape::sphere;
      spec.radius = g.radius;
      spec.centre = g.centre;
      break;
    case GeometryType::cylinder:
      spec.shape = ParticleShape::cylinder;
      spec.radius = g.radius;
      spec.z_min = g.z_min;
      spec.z_max = g.z_max;
      break;
    case GeometryType::box:
      spec.shape = ParticleShape::box;
      spec.lo = g.lo;
      spec.hi = g.hi;
      break;
    case GeometryType::half_disc:
    case GeometryType::rectangle:
      fail(ptr + "/geometry/type", "sph bodies are spheres, cylinders or boxes");
  }
  if (b.grading.enabled) fail(ptr + "/discretization/grading", "sph bodies are not graded");
  spec.sector = to_particle_sector(b.sector);
  spec.lattice = b.lattice;
  spec.spacing = sph_spacing(b);
  spec.boundary_layers = b.sph_boundary_layers;
  spec.jitter = b.sph_jitter;
  spec.jitter_seed = b.seed;
  const SymmetryPlanes planes = sph_symmetry_planes(scene, index);
  try {
    const ParticleCloud cloud = generate_particles(spec);
    if (cloud.size() < 2) fail(ptr + "/discretization", "gives fewer than 2 particles");
    return make_sph_body(b.name, cloud, b.material, b.switches, b.sph, planes, b.velocity,
                         b.temperature, b.seed, nodes);
  } catch (const std::invalid_argument& e) {
    fail(ptr + "/discretization", e.what());
  }
}

SphAbsorbing build_sph_absorbing(const BodySpec& spec, const SphBody& body, const NodeSet& nodes,
                                 std::uint32_t on) {
  return make_sph_absorbing(body, nodes, on, spec.sph_boundary_layers * sph_spacing(spec));
}

}  // namespace splat
