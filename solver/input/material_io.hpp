// Reading and writing material documents (schemas/material.schema.json) and
// the material library of materials/ embedded in the binary.
//
// A document is first validated against the schema; then the rules a schema
// cannot express are checked, in the same `/pointer: rule (unit)` form:
//   /strength/T_melt: must be > T_ref (K)
//   /damage/initial_random_max: must be <= D_max (-)
//   /damage/initiation/theta_max: must be > theta_min (-)
//   /damage/initiation/rate_high: must be > rate_low (1/s)
// and every magnitude against what metals have (density 500 to 25000 kg/m^3,
// E 1 to 1500 GPa, c_p 50 to 5000 J/(kg K), a strength law's stresses 1 MPa
// to 10 GPa (hardening stresses may be 0), T_ref 50 to 1500 K, T_melt 300 to
// 4500 K), naming the unit the value was likely written in:
//   /strength/A: 163 Pa is outside what metals have (1 MPa to 10 GPa); if it
//   was meant in MPa, write 1.63e+08
// The "strength" object is read and written by the parameter list of its law
// (P::fields(), solver/material/strength_law.hpp).
// Defaults for optional fields are those of the Material struct, which equal
// the schema's "default" values (heat_fraction 0.9, D_max 0.9,
// initial_random_max 0); a document without "damage" has no damage.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "solver/input/schema.hpp"
#include "solver/material/material.hpp"

namespace splat {

// Every problem of a material document: schema violations, then the checks
// above (skipped for a field the schema already rejected). Empty = valid.
std::vector<SchemaViolation> material_violations(const nlohmann::json& doc);

// Builds the material; throws InputError listing material_violations(doc).
Material material_from_json(const nlohmann::json& doc);

// The document of a material: valid against the schema, and
// material_from_json(material_to_json(m)) gives m back. Only the parameters
// of the chosen damage models are written; "description" and the source of
// the Mie-Grueneisen numbers are not part of Material and are not written.
nlohmann::json material_to_json(const Material& m);

// Names of the library materials ("al-deck", "al-thesis", ...), sorted.
std::vector<std::string> material_names();

// The document (parsed, not validated) of a library material, or else of a
// JSON file at that path. Throws InputError for a malformed or unreadable
// file, and for a name that is neither: "unknown material 'X' (known: ...;
// or give a path to a JSON file)".
nlohmann::json material_document(std::string_view name_or_path);

// material_from_json(material_document(name_or_path)).
Material load_material(std::string_view name_or_path);

// A material named by text somewhere in a document.
struct MaterialReference {
  std::string pointer;  // of the text: "/bodies/0/material", ".../material/base"
  std::string name;
};

// Every material that `doc` (a scene or any part of one) names by a text that
// is no library material: a file path or an unknown name. Found wherever a
// "material" member is a string, or an object whose "base" is a string.
// Callers that must not read files (the API) refuse these.
std::vector<MaterialReference> non_library_materials(const nlohmann::json& doc);

}  // namespace splat
