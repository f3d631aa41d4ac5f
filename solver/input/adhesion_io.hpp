// The adhesion block of a scene (schemas/scene.schema.json#/definitions/adhesion)
// to and from AdhesionParams. Shared by the two-mass scene and the contact
// interactions. JSON fields and units:
//   G_c        J/m^2   adhesion energy per bonded area
//   sigma_c    Pa      tensile stress cap, or null = none (Griffith form)
//   activation {rule: "none" | "yield-drop" | "temperature" | "surface-expansion",
//               drop_percent (%), homologous_temperature (-),
//               surface_expansion (-), sides: "either" | "both"}
//   D_adh_max  -       damage at which a link erodes, or null = never
#pragma once

#include <nlohmann/json.hpp>

#include "solver/adhesion/cohesive_law.hpp"

namespace splat {

// `j` must already satisfy #/definitions/adhesion (read_scene validates the
// whole document first); absent fields take the schema defaults.
AdhesionParams adhesion_from_json(const nlohmann::json& j);

// Every field written out; adhesion_from_json(adhesion_to_json(p)) == p.
nlohmann::json adhesion_to_json(const AdhesionParams& p);

}  // namespace splat
