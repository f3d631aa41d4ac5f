// The model a particle_impact block expands into (solver/input/impact_scene.hpp):
// the `fidelity` a scene asks for other than auto, and the `model.name` of the
// expanded block and of the run summary.
#pragma once

#include "solver/common/enum_names.hpp"

namespace splat {

enum class Fidelity {
  two_mass,              // rigid masses joined by the link (thesis 3.5.1.1)
  fe_axisym,             // axisymmetric FE particle and substrate
  fe_3d_quarter,         // 3D FE, two symmetry planes
  fe_3d_full,            // 3D FE
  sph_3d_quarter,        // SPH ball on an SPH block, mirrored-ghost symmetry planes
  sph_3d_full,           // SPH ball on an SPH block
  sph_on_fe_3d_quarter,  // SPH ball on a hex FE block, two symmetry planes
  sph_on_fe_3d_full,     // SPH ball on a hex FE block
};

inline constexpr NameTable<Fidelity, 8> k_fidelity_names{{
    {Fidelity::two_mass, "two-mass"},
    {Fidelity::fe_axisym, "fe-axisym"},
    {Fidelity::fe_3d_quarter, "fe-3d-quarter"},
    {Fidelity::fe_3d_full, "fe-3d-full"},
    {Fidelity::sph_3d_quarter, "sph-3d-quarter"},
    {Fidelity::sph_3d_full, "sph-3d-full"},
    {Fidelity::sph_on_fe_3d_quarter, "sph-on-fe-3d-quarter"},
    {Fidelity::sph_on_fe_3d_full, "sph-on-fe-3d-full"},
}};
static_assert(names_in_order(k_fidelity_names));

constexpr const auto& names_of(Fidelity) {
  return k_fidelity_names;
}

constexpr bool is_axisymmetric(Fidelity f) {
  return f == Fidelity::fe_axisym;
}

// Two symmetry planes (x = 0 and y = 0): a quarter of particle and substrate.
constexpr bool is_quarter(Fidelity f) {
  return f == Fidelity::fe_3d_quarter || f == Fidelity::sph_3d_quarter ||
         f == Fidelity::sph_on_fe_3d_quarter;
}

// The whole 3D particle and substrate (an oblique impact needs one).
constexpr bool is_full_3d(Fidelity f) {
  return f == Fidelity::fe_3d_full || f == Fidelity::sph_3d_full ||
         f == Fidelity::sph_on_fe_3d_full;
}

constexpr bool has_sph_substrate(Fidelity f) {
  return f == Fidelity::sph_3d_quarter || f == Fidelity::sph_3d_full;
}

constexpr bool has_sph_particle(Fidelity f) {
  return has_sph_substrate(f) || f == Fidelity::sph_on_fe_3d_quarter ||
         f == Fidelity::sph_on_fe_3d_full;
}

}  // namespace splat
