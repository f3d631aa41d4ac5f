// Boundary conditions on layers of SPH particles (the boundary bits that
// generate_particles gives to every particle within `boundary_layers`
// spacings of a face).
//
//   fixed:     the caller zeroes the velocity of every particle carrying the
//              face's bit (same as FE nodes: solver/core's constraint mask works
//              unchanged on SPH particles).
//   symmetry:  mirrored ghosts, given to make_sph_body as SymmetryPlanes
//              (sph_neighbours.hpp); no constraint is needed.
//   absorbing: impedance forces on the particles of the face's layer,
//                f_i = -A_i (rho0 c_p (v_i . n) n + rho0 c_s (v_i - (v_i . n) n)),
//              with c_p the P-wave and c_s the shear-wave speed. This is thesis
//              eq. 2.1 with its units corrected (the printed form
//              -sqrt(rho / E pi R^2) v.n is not a force): rho c A v has units
//              kg/m^3 m/s m^2 m/s = N. The thesis used A = pi R_SPH^2 on each of
//              three layers, which overstates the face area (it says so); here the
//              face's area is shared over the particles of its layer of thickness
//              t = layers x d, A_i = V_i / t, so the areas of a layer add up to
//              the face area. Normal n: the face's outward axis direction, or the
//              particle's radial outward normal for `curved`. The shear term
//              (as on FE faces) can be switched off to match the thesis.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fe/fe_body.hpp"
#include "solver/sph/sph_body.hpp"

namespace splat {

struct SphAbsorbing {
  std::vector<int> node;     // global node (particle) index
  std::vector<Vec3> normal;  // unit outward normal
  std::vector<double> area;  // A_i, m^2
  double rho_cp = 0.0;       // rho0 c_p, kg/(m^2 s)
  double rho_cs = 0.0;       // rho0 c_s, kg/(m^2 s); 0 = normal part only (thesis)
};

// Absorbing layer on the faces in `on` (BoundaryBit mask; one entry per
// particle and face, so an edge particle of two faces appears twice).
// `layer_thickness` is ParticleCloud::layer_thickness (m, > 0).
SphAbsorbing make_sph_absorbing(const SphBody& body, const NodeSet& nodes, std::uint32_t on,
                                double layer_thickness, bool shear = true);

// Adds the impedance forces to nodes.f; returns the power they absorb,
// -sum f . v >= 0, W.
double apply_sph_absorbing(const SphAbsorbing& a, NodeSet& nodes);

}  // namespace splat
