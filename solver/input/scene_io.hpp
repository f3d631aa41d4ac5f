// Reading a scene document (schemas/scene.schema.json) into a Scene.
//
// Order of work: the document is validated against the schema; then the
// checks a schema cannot express run (unique body names, one dimension per
// scene, geometry allowed for the discretization, references to bodies,
// snapshot times within the run) and every material is resolved. All
// problems are reported together in one InputError whose violations read
// `/json/pointer: rule (unit)`, the pointer locating the offending value in
// the scene document (inside materials too: `/bodies/0/material/strength/A`).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"

namespace splat {

// A scene and the fully resolved document it was read from: every default
// written out and each material inlined as its full document. Reading
// `resolved` again gives the same Scene, so a result file that stores it
// records exactly what ran.
struct LoadedScene {
  Scene scene;
  nlohmann::json resolved;
};

// Validates `doc` and builds the scene. Relative material file paths resolve
// against `base_dir` (the scene file's folder; empty = the working folder).
// Throws InputError listing every violation found.
LoadedScene read_scene(const nlohmann::json& doc, const std::filesystem::path& base_dir = {});

// read_scene(doc, base_dir).scene.
Scene scene_from_json(const nlohmann::json& doc, const std::filesystem::path& base_dir = {});

// read_scene(doc, base_dir).resolved.
nlohmann::json resolved_scene_json(const nlohmann::json& doc,
                                   const std::filesystem::path& base_dir = {});

// A material as a scene names it: a library name, a file path (relative to
// `base_dir`, the scene file's folder; empty = the working folder), an
// inline document, or {"base": NAME, ...fields} merged into NAME's document.
// Throws InputError with every violation, at `pointer` and below it.
Material scene_material(const nlohmann::json& m, const std::filesystem::path& base_dir,
                        const std::string& pointer);

// Applies `/json/pointer=VALUE` overrides in order. VALUE is parsed as JSON;
// text that is not JSON is taken as a string (`/bodies/0/material=cu-deck`).
// The pointer may name a missing member of an existing object (it is created)
// or `-` after an existing array (appended), but never a deeper missing path.
// Throws InputError naming the override on a missing '=', bad pointer syntax,
// a missing parent or an array index out of range.
void apply_overrides(nlohmann::json& doc, const std::vector<std::string>& overrides);

// Reads the scene file, applies the overrides, then read_scene with the
// file's folder as base_dir.
LoadedScene load_scene(const std::filesystem::path& file,
                       const std::vector<std::string>& overrides = {});

}  // namespace splat
