// The cold-spray impact scene: a `particle_impact` block (schemas/scene.schema.json)
// names a particle (material, radius, resolution), a substrate, the impact
// velocity and angle and the adhesion law; expand_particle_impact turns it into
// the bodies, boundary conditions, interactions and time control of an ordinary
// scene, at the fidelity the block asks for or, with `auto`, the cheapest that
// represents it:
//   particle discretization sph, or auto and v > 500 m/s (k_fe_max_velocity:
//   the fastest impact the FE particle mesh survives, docs/verification.md,
//   FE impact robustness)            -> an SPH particle: sph-3d-* (SPH
//                                       substrate) when the substrate asks
//                                       for SPH or its yield stress is below
//                                       sigma_p (it jets too), else
//                                       sph-on-fe-3d-* (hex FE substrate);
//                                       *-quarter for a normal impact (two
//                                       mirrored-ghost symmetry planes),
//                                       *-full for an oblique one
//   angle != 0                       -> fe-3d-full (an oblique impact has one
//                                       symmetry plane at most)
//   angle == 0                       -> fe-axisym
//   substrate "rigid", or "auto" with no adhesion asked and a substrate
//   initial yield stress sigma_0s >= 3 sigma_p (sigma_p: the particle's flow
//   stress at eps_p = 1, 1e7 /s, T_ref; 3 sigma_p bounds the contact pressure
//   a flattening particle exerts, Tabor) -> rigid wall instead of a substrate body
//   no adhesion block                -> plain contact, no adhesion work
//   no D_adh_max and no erosion      -> damage switched off in both bodies
// Geometry (scene coordinates, z up, impact point at the origin):
//   particle: sphere of radius R, centre (0, 0, R (1 + 1e-3)), velocity
//             v (sin a, 0, -cos a);
//   substrate: z in [-S, 0], radius (axisymmetric) or half-width (3D) S, with
//             S = R (4 + v / 250 m/s) capped at 12 R unless given; element size
//             at the impact point equal to the particle's (R / elements_across),
//             growing by 1.15 per element away from it; absorbing boundaries
//             on the far faces (outer radius / sides and bottom).
// SPH levels: particle spacing d = `spacing`, else R / elements_across
// (default 5: the thesis's 2.5 um spacing, SPH radius 1.25 um, at R 12.5 um,
// 743 particles in the full ball); ball centre (0, 0, R + 0.1 d); the SPH
// substrate is a cubic-lattice block of half-width and depth
// S = R (2.4 + v / 1500 m/s), at most 6 R, rounded up to whole spacings
// (2.8 R at 600 m/s: the thesis's 70 x 70 x 35 um block), with absorbing
// layers on the far faces; an FE substrate under an SPH ball is the graded
// hex block above with element size d at the impact point. The SPH body is
// always the contact slave (single pass). `sph` settings of the block apply
// to both SPH bodies (ball HCP, block cubic unless `lattice` is given);
// `erosion` deactivates SPH particles at the damage cap (never deleted).
// The default maximum time is 3 max(t_H, min(R / v, 10 t_H)), with t_H the
// Hertz contact time of the two elastic bodies at v (Johnson 1985, eq. 11.24);
// the adaptive end-time rule of the impact run stops earlier once the outcome
// is decided.
// Output: unless `output` gives snapshot_times or snapshot_count (0 for none),
// 17 field snapshots at max_time i / 16, i = 0..16; a run that stops earlier
// writes its final state as its last snapshot.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/material/material.hpp"
#include "solver/scene/fidelity.hpp"

namespace splat {

// What a particle_impact block asks for, read once; SI units.
struct ImpactRequest {
  nlohmann::json block;      // the particle_impact block as given
  nlohmann::json substrate;  // its substrate block, {} when absent
  nlohmann::json adhesion;   // its adhesion block, {} when absent
  Material particle_material;
  Material substrate_material;  // the particle's when the substrate names none
  double radius = 0.0;          // m
  double velocity = 0.0;        // m/s
  double angle = 0.0;           // degrees from the normal
  bool has_adhesion = false;
  bool damage = false;   // damage in both bodies (asked, or needed by erosion,
                         // D_adh_max or a yield-drop activation)
  bool erosion = false;  // elements at the damage cap are eroded
  std::string fidelity = "auto";
  std::string substrate_type = "auto";  // auto, deformable, rigid
  std::string particle_discretization = "auto";
  std::string substrate_discretization = "auto";
  double particle_flow_stress = 0.0;  // Pa, at eps_p = 1, 1e7 /s, T_ref
};

struct ImpactModelChoice {
  Fidelity model = Fidelity::fe_axisym;  // the model chosen, asked or auto
  bool rigid_substrate = false;
  int elements_across = 0;    // FE elements (or SPH spacings, when no spacing is given) across R
  double element_size = 0.0;  // m: R / elements_across, or the SPH spacing
  std::string why;            // for people: what was chosen and the reason
};

struct ExpandedImpact {
  nlohmann::json scene;  // a scene document with bodies (or two_mass); keeps the block
  ImpactModelChoice choice;
};

// Reads the block of `doc` (materials resolved as a body's, files relative to
// `base_dir`). Throws InputError naming the field of a material that cannot
// be read.
ImpactRequest read_impact_request(const nlohmann::json& doc,
                                  const std::filesystem::path& base_dir = {});

// The model for a request by the rules above (fidelity, discretizations,
// resolution, rigid or deformable substrate) and why. Throws InputError
// naming the field when the request contradicts itself.
ImpactModelChoice choose_model(const ImpactRequest& request);

// `doc` is a scene document with a `particle_impact` block and no bodies,
// already valid against the scene schema; its materials take every form a
// body's do, files relative to `base_dir` (the scene file's folder; empty =
// the working folder). Throws InputError naming the field when the block
// cannot be expanded (unknown material, adhesion asked on a rigid
// substrate, ...).
ExpandedImpact expand_particle_impact(const nlohmann::json& doc,
                                      const std::filesystem::path& base_dir = {});

}  // namespace splat
