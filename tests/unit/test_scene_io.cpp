// Scene documents: valid scenes become the expected Scene, every bad scene is
// reported at the pointer of the offending value with the rule it breaks,
// overrides edit the document before it is read, and the resolved document
// reads back into the same Scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/core/run_summary.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/mesh/mesh.hpp"

namespace splat {
namespace {

using nlohmann::json;

// A copper particle falling on a rigid wall, axisymmetric.
json axisym_scene() {
  return json::parse(R"({
    "name": "cu-particle-on-wall",
    "description": "A copper particle hits a rigid wall at 500 m/s.",
    "bodies": [{
      "name": "particle",
      "material": "cu-deck",
      "geometry": {"type": "half-disc", "radius": 10e-6, "z_centre": 10e-6},
      "discretization": {"type": "fe-axisym", "elements_across": 20},
      "initial": {"velocity": [0, 0, -500]}
    }],
    "interactions": [{"type": "rigid-wall", "point": [0, 0, 0], "normal": [0, 0, 2]}],
    "time": {"end_time": 40e-9}
  })");
}

// A quarter copper sphere on an aluminium block, 3D.
json hex_scene() {
  return json::parse(R"({
    "name": "cu-on-al-3d",
    "bodies": [
      {
        "name": "particle",
        "material": "cu-deck",
        "geometry": {"type": "sphere", "radius": 10e-6, "centre": [0, 0, 10.5e-6]},
        "discretization": {"type": "fe-hex", "elements_across": 8, "sector": "quarter",
                           "grading": {"focus": [0, 0, 0.5e-6], "ratio": 1.1}},
        "initial": {"velocity": [0, 0, -600], "temperature": 400, "seed": 7},
        "switches": {"damage": false},
        "hourglass": {"type": "stiffness", "coefficient": 0.05},
        "artificial_viscosity": {"linear": 0.1},
        "erosion": {"enabled": true, "min_time_step": 1e-13}
      },
      {
        "name": "substrate",
        "material": "al-deck",
        "geometry": {"type": "box", "min": [0, 0, -30e-6], "max": [30e-6, 30e-6, 0]},
        "discretization": {"type": "fe-hex", "element_size": 1e-6}
      }
    ],
    "boundary_conditions": [
      {"body": "substrate", "on": "z_min", "type": "fixed"},
      {"body": "substrate", "on": "x_max", "type": "absorbing"},
      {"body": "particle", "on": "x_min", "type": "symmetry"},
      {"body": "substrate", "on": "y_max", "type": "velocity", "velocity": [0, 0, 1]}
    ],
    "interactions": [{"type": "rigid-wall", "bodies": ["substrate"], "point": [0, 0, -31e-6],
                      "normal": [0, 0, 1]}],
    "time": {"end_time": 60e-9, "stability_coefficient": 0.5, "max_steps": 1000,
             "wall_clock_limit": 30, "energy_balance_limit": 0.1},
    "output": {"snapshot_times": [0, 30e-9, 60e-9], "history_interval": 1e-9}
  })");
}

std::vector<SchemaViolation> violations_of(const json& doc) {
  try {
    scene_from_json(doc);
  } catch (const InputError& e) {
    return e.violations();
  }
  return {};
}

std::string listing(const std::vector<SchemaViolation>& violations) {
  std::string out;
  for (const SchemaViolation& v : violations) out += "\n  " + to_string(v);
  return out.empty() ? "\n  (none)" : out;
}

// The scene is rejected with a violation at `pointer` whose rule contains `words`.
void expect_violation(const json& doc, const std::string& pointer, const std::string& words) {
  const std::vector<SchemaViolation> violations = violations_of(doc);
  bool found = false;
  for (const SchemaViolation& v : violations) {
    found |= v.pointer == pointer && v.message.find(words) != std::string::npos;
  }
  EXPECT_TRUE(found) << "expected " << pointer << ": ..." << words << "...; got"
                     << listing(violations);
}

TEST(SceneIo, minimal_axisymmetric_scene) {
  const Scene s = scene_from_json(axisym_scene());
  EXPECT_EQ(s.name, "cu-particle-on-wall");
  EXPECT_EQ(s.description, "A copper particle hits a rigid wall at 500 m/s.");
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodySpec& b = s.bodies[0];
  EXPECT_EQ(b.name, "particle");
  EXPECT_EQ(b.material.name, "cu-deck");
  EXPECT_DOUBLE_EQ(std::get<JohnsonCookParams>(b.material.strength).A, 160e6);
  EXPECT_EQ(b.geometry.type, GeometryType::half_disc);
  EXPECT_DOUBLE_EQ(b.geometry.radius, 10e-6);
  EXPECT_DOUBLE_EQ(b.geometry.centre.z(), 10e-6);
  EXPECT_EQ(b.discretization, Discretization::fe_axisym);
  EXPECT_EQ(b.elements_across, 20);
  EXPECT_EQ(b.element_size, 0.0);
  EXPECT_EQ(b.velocity, Vec3(0, 0, -500));
  ASSERT_EQ(s.interactions.size(), 1u);
  EXPECT_EQ(s.interactions[0].type, InteractionType::rigid_wall);
  EXPECT_TRUE(s.interactions[0].bodies.empty());
  EXPECT_EQ(s.interactions[0].normal, Vec3(0, 0, 1));  // normalised
  EXPECT_DOUBLE_EQ(s.time.end_time, 40e-9);
}

TEST(SceneIo, defaults_are_filled) {
  const Scene s = scene_from_json(axisym_scene());
  const BodySpec& b = s.bodies[0];
  EXPECT_DOUBLE_EQ(b.temperature,
                   std::get<JohnsonCookParams>(b.material.strength).T_ref);  // 300 K for cu-deck
  EXPECT_EQ(b.seed, 1u);
  EXPECT_EQ(b.sector, SectorKind::full);
  EXPECT_FALSE(b.grading.enabled);
  EXPECT_TRUE(b.switches.damage && b.switches.thermal_softening && b.switches.rate_hardening &&
              b.switches.adiabatic_heating);
  EXPECT_EQ(b.hourglass, HourglassType::viscous);
  EXPECT_DOUBLE_EQ(b.hourglass_coefficient, 0.1);
  EXPECT_DOUBLE_EQ(b.q_linear, 0.06);
  EXPECT_DOUBLE_EQ(b.q_quadratic, 1.5);
  EXPECT_FALSE(b.erosion);
  EXPECT_EQ(b.erosion_min_time_step, 0.0);
  EXPECT_DOUBLE_EQ(s.time.stability_coefficient, 0.9);
  EXPECT_EQ(s.time.max_steps, 10'000'000);
  EXPECT_EQ(s.time.min_time_step, 0.0);
  EXPECT_EQ(s.time.wall_clock_limit, 0.0);
  EXPECT_DOUBLE_EQ(s.time.energy_balance_limit, 0.05);
  EXPECT_TRUE(s.output.snapshot_times.empty());
  EXPECT_EQ(s.output.history_interval, 0.0);
  EXPECT_TRUE(s.boundaries.empty());
}

TEST(SceneIo, three_dimensional_scene) {
  const Scene s = scene_from_json(hex_scene());
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodySpec& p = s.bodies[0];
  EXPECT_EQ(p.geometry.type, GeometryType::sphere);
  EXPECT_EQ(p.geometry.centre, Vec3(0, 0, 10.5e-6));
  EXPECT_EQ(p.discretization, Discretization::fe_hex);
  EXPECT_EQ(p.sector, SectorKind::quarter);
  EXPECT_TRUE(p.grading.enabled);
  EXPECT_EQ(p.grading.focus, Vec3(0, 0, 0.5e-6));
  EXPECT_DOUBLE_EQ(p.grading.ratio, 1.1);
  EXPECT_DOUBLE_EQ(p.temperature, 400.0);
  EXPECT_EQ(p.seed, 7u);
  EXPECT_FALSE(p.switches.damage);
  EXPECT_TRUE(p.switches.adiabatic_heating);
  EXPECT_EQ(p.hourglass, HourglassType::stiffness);
  EXPECT_DOUBLE_EQ(p.hourglass_coefficient, 0.05);
  EXPECT_DOUBLE_EQ(p.q_linear, 0.1);
  EXPECT_DOUBLE_EQ(p.q_quadratic, 1.5);
  EXPECT_TRUE(p.erosion);
  EXPECT_DOUBLE_EQ(p.erosion_min_time_step, 1e-13);

  const BodySpec& sub = s.bodies[1];
  EXPECT_EQ(sub.material.name, "al-deck");
  EXPECT_EQ(sub.geometry.type, GeometryType::box);
  EXPECT_EQ(sub.geometry.lo, Vec3(0, 0, -30e-6));
  EXPECT_EQ(sub.geometry.hi, Vec3(30e-6, 30e-6, 0));
  EXPECT_EQ(sub.elements_across, 0);
  EXPECT_DOUBLE_EQ(sub.element_size, 1e-6);

  ASSERT_EQ(s.boundaries.size(), 4u);
  EXPECT_EQ(s.boundaries[0].body, "substrate");
  EXPECT_EQ(s.boundaries[0].on, boundary_z_min);
  EXPECT_EQ(s.boundaries[0].type, BoundaryType::fixed);
  EXPECT_EQ(s.boundaries[1].on, boundary_x_max);
  EXPECT_EQ(s.boundaries[1].type, BoundaryType::absorbing);
  EXPECT_EQ(s.boundaries[2].on, boundary_x_min);
  EXPECT_EQ(s.boundaries[2].type, BoundaryType::symmetry);
  EXPECT_EQ(s.boundaries[3].type, BoundaryType::velocity);
  EXPECT_EQ(s.boundaries[3].velocity, Vec3(0, 0, 1));

  ASSERT_EQ(s.interactions.size(), 1u);
  EXPECT_EQ(s.interactions[0].bodies, std::vector<std::string>{"substrate"});
  EXPECT_EQ(s.interactions[0].point, Vec3(0, 0, -31e-6));

  EXPECT_DOUBLE_EQ(s.time.stability_coefficient, 0.5);
  EXPECT_EQ(s.time.max_steps, 1000);
  EXPECT_DOUBLE_EQ(s.time.wall_clock_limit, 30.0);
  EXPECT_DOUBLE_EQ(s.time.energy_balance_limit, 0.1);
  EXPECT_EQ(s.output.snapshot_times, (std::vector<double>{0, 30e-9, 60e-9}));
  EXPECT_DOUBLE_EQ(s.output.history_interval, 1e-9);
}

TEST(SceneIo, axisymmetric_boundary_names_and_grading) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"] = {
      {"type", "rectangle"}, {"r_max", 1e-3}, {"z_min", 0.0}, {"z_max", 50e-3}};
  doc["bodies"][0]["discretization"]["grading"] = {{"focus", {1e-4, 0, 2e-3}}, {"ratio", 1.05}};
  doc["boundary_conditions"] = {{{"body", "particle"}, {"on", "axis"}, {"type", "symmetry"}},
                                {{"body", "particle"}, {"on", "bottom"}, {"type", "fixed"}},
                                {{"body", "particle"}, {"on", "top"}, {"type", "absorbing"}},
                                {{"body", "particle"}, {"on", "outer"}, {"type", "fixed"}}};
  const Scene s = scene_from_json(doc);
  EXPECT_EQ(s.bodies[0].geometry.type, GeometryType::rectangle);
  EXPECT_DOUBLE_EQ(s.bodies[0].geometry.radius, 1e-3);
  EXPECT_DOUBLE_EQ(s.bodies[0].geometry.z_max, 50e-3);
  EXPECT_EQ(s.bodies[0].grading.focus, Vec3(1e-4, 0, 2e-3));  // scene coordinates [r, 0, z]
  ASSERT_EQ(s.boundaries.size(), 4u);
  EXPECT_EQ(s.boundaries[0].on, boundary_x_min);
  EXPECT_EQ(s.boundaries[1].on, boundary_y_min);
  EXPECT_EQ(s.boundaries[2].on, boundary_y_max);
  EXPECT_EQ(s.boundaries[3].on, boundary_x_max);

  doc["boundary_conditions"][1]["on"] = "z_min";
  expect_violation(doc, "/boundary_conditions/1/on", "bottom");
}

TEST(SceneIo, grading_uniform_extent_is_read_checked_and_written_back) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"] = {
      {"type", "rectangle"}, {"r_max", 1e-3}, {"z_min", 0.0}, {"z_max", 50e-3}};
  json& g = doc["bodies"][0]["discretization"]["grading"];
  g = {{"focus", {0, 0, 50e-3}}, {"ratio", 1.1}, {"uniform_extent", {2e-4, 0, 1e-4}}};
  const LoadedScene loaded = read_scene(doc);
  EXPECT_EQ(loaded.scene.bodies[0].grading.uniform_extent, Vec3(2e-4, 0, 1e-4));
  EXPECT_EQ(loaded.resolved["bodies"][0]["discretization"]["grading"]["uniform_extent"],
            json({2e-4, 0.0, 1e-4}));

  g["uniform_extent"] = {2e-4, 0, -1e-4};
  expect_violation(doc, "/bodies/0/discretization/grading/uniform_extent/2", ">= 0");
  g["uniform_extent"] = {2e-4, 1e-4, 1e-4};
  expect_violation(doc, "/bodies/0/discretization/grading/uniform_extent/1", "must be 0");
  g["uniform_extent"] = {2e-4, 0, 1e-4};
  doc["bodies"][0]["geometry"] = {{"type", "half-disc"}, {"radius", 10e-6}, {"z_centre", 0.0}};
  expect_violation(doc, "/bodies/0/discretization/grading/uniform_extent",
                   "rectangle and box geometries only");
}

TEST(SceneIo, snapshot_count_gives_evenly_spaced_times_ending_at_end_time) {
  json doc = axisym_scene();
  doc["output"] = {{"snapshot_count", 4}};
  const Scene s = scene_from_json(doc);
  ASSERT_EQ(s.output.snapshot_times.size(), 4u);
  EXPECT_DOUBLE_EQ(s.output.snapshot_times[0], 10e-9);
  EXPECT_DOUBLE_EQ(s.output.snapshot_times[1], 20e-9);
  EXPECT_EQ(s.output.snapshot_times[3], 40e-9);
}

TEST(SceneIo, library_inline_and_base_override_materials) {
  json doc = axisym_scene();

  json inline_material = material_to_json(load_material("al-deck"));
  inline_material["name"] = "my-al";
  inline_material["strength"]["A"] = 123e6;
  doc["bodies"][0]["material"] = inline_material;
  Scene s = scene_from_json(doc);
  EXPECT_EQ(s.bodies[0].material.name, "my-al");
  EXPECT_DOUBLE_EQ(std::get<JohnsonCookParams>(s.bodies[0].material.strength).A, 123e6);

  doc["bodies"][0]["material"] = {{"base", "cu-deck"}, {"strength", {{"A", 100e6}}}};
  s = scene_from_json(doc);
  const Material cu = load_material("cu-deck");
  EXPECT_EQ(s.bodies[0].material.name, "cu-deck");
  EXPECT_DOUBLE_EQ(std::get<JohnsonCookParams>(s.bodies[0].material.strength).A, 100e6);
  EXPECT_DOUBLE_EQ(std::get<JohnsonCookParams>(s.bodies[0].material.strength).B,
                   std::get<JohnsonCookParams>(cu.strength).B);  // kept from the base
  EXPECT_DOUBLE_EQ(s.bodies[0].material.density, cu.density);
}

TEST(SceneIo, material_file_relative_to_the_scene_file) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("splat_scene_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "mat");
  json material = material_to_json(load_material("cu-deck"));
  material["name"] = "soft-cu";
  material["strength"]["A"] = 50e6;
  std::ofstream(dir / "mat" / "soft-cu.json") << material.dump(2);
  json doc = axisym_scene();
  doc["bodies"][0]["material"] = "mat/soft-cu.json";
  std::ofstream(dir / "scene.json") << doc.dump(2);

  const LoadedScene loaded = load_scene(dir / "scene.json", {"/time/end_time=2e-8"});
  EXPECT_EQ(loaded.scene.bodies[0].material.name, "soft-cu");
  EXPECT_DOUBLE_EQ(std::get<JohnsonCookParams>(loaded.scene.bodies[0].material.strength).A, 50e6);
  EXPECT_DOUBLE_EQ(loaded.scene.time.end_time, 2e-8);
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- bad scenes

TEST(SceneIo, negative_radius) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"]["radius"] = -1e-6;
  expect_violation(doc, "/bodies/0/geometry/radius", "must be > 0 (m)");
}

TEST(SceneIo, unknown_geometry_type) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"]["type"] = "torus";
  expect_violation(doc, "/bodies/0/geometry/type", "must be one of \"sphere\"");
}

TEST(SceneIo, geometry_field_of_another_type) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"]["z_min"] = 0.0;
  expect_violation(doc, "/bodies/0/geometry/z_min", "unknown field");
  doc = axisym_scene();
  doc["bodies"][0]["geometry"].erase("z_centre");
  expect_violation(doc, "/bodies/0/geometry/z_centre", "required field is missing");
}

TEST(SceneIo, unknown_material_name) {
  json doc = axisym_scene();
  doc["bodies"][0]["material"] = "unobtainium";
  expect_violation(doc, "/bodies/0/material", "unknown material 'unobtainium'");
}

TEST(SceneIo, override_pushing_material_strength_negative) {
  json doc = axisym_scene();
  doc["bodies"][0]["material"] = {{"base", "cu-deck"}, {"strength", {{"A", -1.0}}}};
  expect_violation(doc, "/bodies/0/material/strength/A", "must be >= 0 (Pa)");
}

TEST(SceneIo, unknown_base_material) {
  json doc = axisym_scene();
  doc["bodies"][0]["material"] = {{"base", "unobtainium"}};
  expect_violation(doc, "/bodies/0/material/base", "unknown material 'unobtainium'");
}

TEST(SceneIo, box_with_fe_axisym) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"] = {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}};
  expect_violation(doc, "/bodies/0/geometry/type", "box needs fe-hex");
}

TEST(SceneIo, half_disc_with_fe_hex) {
  json doc = axisym_scene();
  doc["bodies"][0]["discretization"]["type"] = "fe-hex";
  expect_violation(doc, "/bodies/0/geometry/type", "half-disc needs fe-axisym");
}

TEST(SceneIo, sphere_off_the_axis_with_fe_axisym) {
  json doc = axisym_scene();
  doc["bodies"][0]["geometry"] = {{"type", "sphere"}, {"radius", 1e-5}, {"centre", {1e-6, 0, 0}}};
  expect_violation(doc, "/bodies/0/geometry/centre", "must lie on the axis");
}

TEST(SceneIo, mixed_dimensions) {
  json doc = hex_scene();
  doc["bodies"][1]["discretization"]["type"] = "fe-axisym";
  doc["bodies"][1]["geometry"] = {
      {"type", "rectangle"}, {"r_max", 1e-5}, {"z_min", -1e-5}, {"z_max", 0.0}};
  expect_violation(doc, "/bodies/1/discretization/type", "cannot be mixed");
}

TEST(SceneIo, sph_body_settings_round_trip) {
  json doc = hex_scene();
  doc["bodies"][0]["discretization"] = {{"type", "sph"},
                                        {"elements_across", 8},
                                        {"sector", "quarter"},
                                        {"sph",
                                         {{"lattice", "cubic"},
                                          {"kernel", "wendland-c2"},
                                          {"viscosity_linear", 0.5},
                                          {"hourglass_coefficient", 0.3},
                                          {"update_threshold", 0.7},
                                          {"boundary_layers", 2}}}};
  const LoadedScene loaded = read_scene(doc);
  const BodySpec& b = loaded.scene.bodies[0];
  EXPECT_EQ(b.discretization, Discretization::sph);
  EXPECT_EQ(b.sector, SectorKind::quarter);
  EXPECT_EQ(b.lattice, Lattice::cubic);
  EXPECT_EQ(b.sph.kernel, SphKernel::wendland_c2);
  EXPECT_EQ(b.sph.visc_linear, 0.5);
  EXPECT_EQ(b.sph.visc_quadratic, 4.0);  // thesis default
  EXPECT_EQ(b.sph.hourglass_coefficient, 0.3);
  EXPECT_EQ(b.sph.update_threshold, 0.7);
  EXPECT_EQ(b.sph_boundary_layers, 2);
  // The resolved scene states every setting and reads back to the same body.
  const json& d = loaded.resolved["bodies"][0]["discretization"];
  EXPECT_EQ(d["sph"]["viscosity_quadratic"], 4.0);
  const LoadedScene again = read_scene(loaded.resolved);
  EXPECT_EQ(again.resolved, loaded.resolved);
}

TEST(SceneIo, sph_settings_only_on_sph_bodies) {
  json doc = hex_scene();
  doc["bodies"][0]["discretization"]["sph"] = {{"lattice", "hcp"}};
  expect_violation(doc, "/bodies/0/discretization/sph", "only sph bodies take sph settings");
}

TEST(SceneIo, duplicate_body_names) {
  json doc = hex_scene();
  doc["bodies"][1]["name"] = "particle";
  expect_violation(doc, "/bodies/1/name", "duplicate body name \"particle\"");
}

TEST(SceneIo, boundary_on_unknown_body) {
  json doc = hex_scene();
  doc["boundary_conditions"][0]["body"] = "plate";
  expect_violation(doc, "/boundary_conditions/0/body", "no body named \"plate\"");
}

TEST(SceneIo, interaction_with_unknown_body_and_zero_normal) {
  json doc = hex_scene();
  doc["interactions"][0]["bodies"] = {"substrate", "plate"};
  doc["interactions"][0]["normal"] = {0, 0, 0};
  expect_violation(doc, "/interactions/0/bodies/1", "no body named \"plate\"");
  expect_violation(doc, "/interactions/0/normal", "must be non-zero");
}

TEST(SceneIo, contact_interaction) {
  json doc = hex_scene();
  doc["interactions"].push_back(
      {{"type", "contact"}, {"master", "substrate"}, {"slave", "particle"}, {"friction", 0.2}});
  const LoadedScene loaded = read_scene(doc);
  ASSERT_EQ(loaded.scene.interactions.size(), 2u);
  const InteractionSpec& c = loaded.scene.interactions[1];
  EXPECT_EQ(c.type, InteractionType::contact);
  EXPECT_EQ(c.master, "substrate");
  EXPECT_EQ(c.slave, "particle");
  EXPECT_EQ(c.method, ContactMethod::lagrange);
  EXPECT_EQ(c.solver, ContactSolverKind::pgs);
  EXPECT_EQ(c.friction, 0.2);
  // The resolved document reads back into the same interaction.
  const Scene again = scene_from_json(loaded.resolved);
  EXPECT_EQ(again.interactions[1].master, "substrate");
  EXPECT_EQ(again.interactions[1].friction, 0.2);
  EXPECT_EQ(again.interactions[1].method, ContactMethod::lagrange);
}

TEST(SceneIo, contact_errors_name_their_field) {
  json doc = hex_scene();
  doc["interactions"] = {{{"type", "contact"}, {"master", "plate"}, {"slave", "particle"}}};
  expect_violation(doc, "/interactions/0/master", "no body named \"plate\"");
  doc["interactions"][0]["master"] = "particle";
  expect_violation(doc, "/interactions/0/slave", "must differ from master");
  doc["interactions"][0]["master"] = "substrate";
  doc["interactions"][0]["friction"] = -0.1;
  expect_violation(doc, "/interactions/0/friction", "must be >= 0");
  doc["interactions"][0]["friction"] = 0.1;
  doc["interactions"][0]["solver"] = "active-set";
  expect_violation(doc, "/interactions/0/solver", "frictionless");
  doc["interactions"][0]["solver"] = "pgs";
  doc["interactions"][0]["penalty_stiffness"] = 1e15;
  expect_violation(doc, "/interactions/0/penalty_stiffness", "only with method");
  doc["interactions"][0]["point"] = {0, 0, 0};
  expect_violation(doc, "/interactions/0/point", "");
}

TEST(SceneIo, symmetry_on_the_curved_surface) {
  json doc = hex_scene();
  doc["boundary_conditions"][2]["on"] = "curved";
  expect_violation(doc, "/boundary_conditions/2/on", "needs a plane");
}

TEST(SceneIo, axisymmetric_wall_normal_off_the_axis) {
  json doc = axisym_scene();
  doc["interactions"][0]["normal"] = {1, 0, 1};
  expect_violation(doc, "/interactions/0/normal", "must be along z");
}

TEST(SceneIo, stability_coefficient_above_one) {
  json doc = axisym_scene();
  doc["time"]["stability_coefficient"] = 1.5;
  expect_violation(doc, "/time/stability_coefficient", "must be <= 1 (-)");
}

TEST(SceneIo, zero_elements_across) {
  json doc = axisym_scene();
  doc["bodies"][0]["discretization"]["elements_across"] = 0;
  expect_violation(doc, "/bodies/0/discretization/elements_across", "must be >= 1 (-)");
}

TEST(SceneIo, both_elements_across_and_element_size) {
  json doc = axisym_scene();
  doc["bodies"][0]["discretization"]["element_size"] = 1e-6;
  expect_violation(doc, "/bodies/0/discretization", "not both");
  doc["bodies"][0]["discretization"].erase("element_size");
  doc["bodies"][0]["discretization"].erase("elements_across");
  expect_violation(doc, "/bodies/0/discretization", "needs elements_across or element_size");
}

TEST(SceneIo, snapshot_time_after_end_time) {
  json doc = axisym_scene();
  doc["output"] = {{"snapshot_times", {10e-9, 50e-9}}};
  expect_violation(doc, "/output/snapshot_times/1", "must be <= end_time (s)");
}

TEST(SceneIo, axisymmetric_body_with_x_velocity) {
  json doc = axisym_scene();
  doc["bodies"][0]["initial"]["velocity"] = {10, 0, -500};
  expect_violation(doc, "/bodies/0/initial/velocity/0", "must be 0 for fe-axisym");
}

TEST(SceneIo, z_max_below_z_min_and_inverted_box) {
  json doc = hex_scene();
  doc["bodies"][1]["geometry"]["max"][1] = -1.0;
  expect_violation(doc, "/bodies/1/geometry/max/1", "must be > min/1 (m)");
  doc = axisym_scene();
  doc["bodies"][0]["geometry"] = {
      {"type", "rectangle"}, {"r_max", 1e-3}, {"z_min", 1.0}, {"z_max", 1.0}};
  expect_violation(doc, "/bodies/0/geometry/z_max", "must be > z_min (m)");
}

TEST(SceneIo, velocity_boundary_needs_a_velocity) {
  json doc = hex_scene();
  doc["boundary_conditions"][3].erase("velocity");
  expect_violation(doc, "/boundary_conditions/3/velocity", "required field is missing");
}

TEST(SceneIo, all_problems_are_reported_together) {
  json doc = hex_scene();
  doc["bodies"].push_back(doc["bodies"][0]);
  doc["boundary_conditions"][0]["body"] = "plate";
  doc["output"]["snapshot_times"] = {0, 70e-9};
  EXPECT_EQ(violations_of(doc).size(), 3u) << listing(violations_of(doc));
}

// ---------------------------------------------------------------- overrides

TEST(SceneIo, override_replaces_a_number) {
  json doc = axisym_scene();
  apply_overrides(doc, {"/bodies/0/initial/velocity/2=-800", "/time/end_time=1e-8"});
  EXPECT_EQ(doc["bodies"][0]["initial"]["velocity"][2], -800);
  EXPECT_EQ(scene_from_json(doc).time.end_time, 1e-8);
}

TEST(SceneIo, override_creates_a_missing_last_member) {
  json doc = axisym_scene();
  apply_overrides(doc, {"/time/max_steps=500", "/output={\"snapshot_count\": 2}"});
  const Scene s = scene_from_json(doc);
  EXPECT_EQ(s.time.max_steps, 500);
  EXPECT_EQ(s.output.snapshot_times.size(), 2u);
}

TEST(SceneIo, override_creates_missing_objects_and_the_schema_names_a_misspelt_one) {
  json doc = axisym_scene();
  doc.erase("output");
  apply_overrides(doc, {"/output/snapshot_count=2"});
  EXPECT_EQ(scene_from_json(doc).output.snapshot_times.size(), 2u);
  apply_overrides(doc, {"/timing/end_time=1e-8"});
  EXPECT_EQ(doc["timing"]["end_time"], 1e-8);
  EXPECT_NE(listing(violations_of(doc)).find("timing"), std::string::npos)
      << listing(violations_of(doc));
}

TEST(SceneIo, override_value_that_is_not_json_is_a_string) {
  json doc = axisym_scene();
  apply_overrides(doc, {"/bodies/0/material=al-deck", "/name=run-2"});
  EXPECT_EQ(doc["bodies"][0]["material"], "al-deck");
  EXPECT_EQ(scene_from_json(doc).bodies[0].material.name, "al-deck");
  EXPECT_EQ(doc["name"], "run-2");
}

TEST(SceneIo, override_appends_to_an_array) {
  json doc = axisym_scene();
  apply_overrides(doc, {"/interactions/-={\"type\": \"rigid-wall\", \"point\": [0, 0, 1], "
                        "\"normal\": [0, 0, -1]}"});
  EXPECT_EQ(scene_from_json(doc).interactions.size(), 2u);
}

std::string override_error(const std::vector<std::string>& overrides) {
  json doc = axisym_scene();
  try {
    apply_overrides(doc, overrides);
  } catch (const InputError& e) {
    EXPECT_EQ(e.violations().size(), 1u);
    return e.what();
  }
  return "(no error)";
}

TEST(SceneIo, bad_overrides_name_the_override) {
  EXPECT_NE(override_error({"/time/end_time"}).find("override '/time/end_time': expected"),
            std::string::npos);
  EXPECT_NE(override_error({"time/end_time=1"}).find("must start with '/'"), std::string::npos);
  EXPECT_NE(override_error({"/time/a~2b=1"}).find("bad JSON pointer"), std::string::npos);
  EXPECT_NE(override_error({"/bodies/3={}"}).find("index 3 out of range"), std::string::npos);
  EXPECT_NE(override_error({"/bodies/3/name/x=1"}).find("/bodies/3 does not exist"),
            std::string::npos);
  EXPECT_NE(override_error({"/name/x=1"}).find("/name is not an object or array"),
            std::string::npos);
}

// A velocity condition with a tabulated history on the 3D scene's substrate.
json history_condition() {
  return json::parse(R"({"body": "substrate", "on": "y_max", "type": "velocity", "name": "grip",
    "components": ["x", "z"],
    "history": {"time": [0, 1e-9, 5e-9], "velocity": [[0, 0, 0], [0, 0, 2], [0, 0, 2]]}})");
}

TEST(SceneIo, velocity_history_is_read) {
  json doc = hex_scene();
  doc["boundary_conditions"][3] = history_condition();
  const Scene s = scene_from_json(doc);
  const BoundarySpec& bc = s.boundaries[3];
  EXPECT_EQ(bc.name, "grip");
  EXPECT_EQ(bc.components, (std::array<bool, 3>{true, false, true}));
  ASSERT_TRUE(bc.history.has_value());
  EXPECT_EQ(bc.history->time, (std::vector<double>{0, 1e-9, 5e-9}));
  EXPECT_EQ(bc.history->velocity[1], Vec3(0, 0, 2));
  EXPECT_EQ(bc.history->interpolation, HistoryInterpolation::linear);
}

TEST(SceneIo, bad_velocity_histories_name_the_field) {
  json doc = hex_scene();
  doc["boundary_conditions"][3] = history_condition();
  json d = doc;
  d["boundary_conditions"][3]["history"]["time"] = {0, 2e-9, 2e-9};
  expect_violation(d, "/boundary_conditions/3/history/time/2", "must exceed the time before it");
  d = doc;
  d["boundary_conditions"][3]["history"]["velocity"].push_back({0, 0, 1});
  expect_violation(d, "/boundary_conditions/3/history/velocity", "has 4 rows but time has 3");
  d = doc;
  d["boundary_conditions"][3]["history"]["time"][0] = -1e-9;
  expect_violation(d, "/boundary_conditions/3/history/time/0", ">= 0");
  d = doc;
  d["boundary_conditions"][3]["velocity"] = {0, 0, 1};
  expect_violation(d, "/boundary_conditions/3/history", "not both");
  d = doc;
  d["boundary_conditions"][3]["history"]["interpolation"] = "cubic";
  expect_violation(d, "/boundary_conditions/3/history/interpolation", "");
  d = doc;
  d["boundary_conditions"][3]["components"] = {"z", "z"};
  expect_violation(d, "/boundary_conditions/3/components/1", "listed twice");
  d = doc;
  d["boundary_conditions"][2]["name"] = "grip";
  expect_violation(d, "/boundary_conditions/3/name", "duplicate boundary-condition name");
  d = doc;
  d["boundary_conditions"][2]["components"] = {"x"};
  expect_violation(d, "/boundary_conditions/2/components", "unknown field");
}

TEST(SceneIo, axisymmetric_velocity_history_has_no_y) {
  json doc = axisym_scene();
  doc["boundary_conditions"] = json::parse(R"([{"body": "particle", "on": "curved",
    "type": "velocity", "components": ["y"],
    "history": {"time": [0, 1e-9], "velocity": [[0, 0, 0], [0, 3, -1]]}}])");
  expect_violation(doc, "/boundary_conditions/0/components", "not y");
  expect_violation(doc, "/boundary_conditions/0/history/velocity/1/1", "must be 0 for fe-axisym");
}

// ---------------------------------------------------------------- resolved document

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodySpec& x = a.bodies[i];
    const BodySpec& y = b.bodies[i];
    EXPECT_EQ(material_to_json(x.material), material_to_json(y.material));
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.geometry.type, y.geometry.type);
    EXPECT_EQ(x.geometry.radius, y.geometry.radius);
    EXPECT_EQ(x.geometry.centre, y.geometry.centre);
    EXPECT_EQ(x.geometry.z_min, y.geometry.z_min);
    EXPECT_EQ(x.geometry.z_max, y.geometry.z_max);
    EXPECT_EQ(x.geometry.lo, y.geometry.lo);
    EXPECT_EQ(x.geometry.hi, y.geometry.hi);
    EXPECT_EQ(x.discretization, y.discretization);
    EXPECT_EQ(x.elements_across, y.elements_across);
    EXPECT_EQ(x.element_size, y.element_size);
    EXPECT_EQ(x.sector, y.sector);
    EXPECT_EQ(x.grading.enabled, y.grading.enabled);
    EXPECT_EQ(x.grading.focus, y.grading.focus);
    EXPECT_EQ(x.grading.ratio, y.grading.ratio);
    EXPECT_EQ(x.grading.uniform_extent, y.grading.uniform_extent);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.temperature, y.temperature);
    EXPECT_EQ(x.seed, y.seed);
    EXPECT_EQ(x.switches.damage, y.switches.damage);
    EXPECT_EQ(x.switches.thermal_softening, y.switches.thermal_softening);
    EXPECT_EQ(x.switches.rate_hardening, y.switches.rate_hardening);
    EXPECT_EQ(x.switches.adiabatic_heating, y.switches.adiabatic_heating);
    EXPECT_EQ(x.hourglass, y.hourglass);
    EXPECT_EQ(x.hourglass_coefficient, y.hourglass_coefficient);
    EXPECT_EQ(x.q_linear, y.q_linear);
    EXPECT_EQ(x.q_quadratic, y.q_quadratic);
    EXPECT_EQ(x.erosion, y.erosion);
    EXPECT_EQ(x.erosion_min_time_step, y.erosion_min_time_step);
  }
  ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
  for (std::size_t i = 0; i < a.boundaries.size(); ++i) {
    EXPECT_EQ(a.boundaries[i].body, b.boundaries[i].body);
    EXPECT_EQ(a.boundaries[i].on, b.boundaries[i].on);
    EXPECT_EQ(a.boundaries[i].type, b.boundaries[i].type);
    EXPECT_EQ(a.boundaries[i].velocity, b.boundaries[i].velocity);
    EXPECT_EQ(a.boundaries[i].name, b.boundaries[i].name);
    EXPECT_EQ(a.boundaries[i].components, b.boundaries[i].components);
    ASSERT_EQ(a.boundaries[i].history.has_value(), b.boundaries[i].history.has_value());
    if (a.boundaries[i].history) {
      EXPECT_EQ(a.boundaries[i].history->time, b.boundaries[i].history->time);
      EXPECT_EQ(a.boundaries[i].history->velocity, b.boundaries[i].history->velocity);
      EXPECT_EQ(a.boundaries[i].history->interpolation, b.boundaries[i].history->interpolation);
    }
  }
  ASSERT_EQ(a.interactions.size(), b.interactions.size());
  for (std::size_t i = 0; i < a.interactions.size(); ++i) {
    EXPECT_EQ(a.interactions[i].type, b.interactions[i].type);
    EXPECT_EQ(a.interactions[i].bodies, b.interactions[i].bodies);
    EXPECT_EQ(a.interactions[i].point, b.interactions[i].point);
    EXPECT_EQ(a.interactions[i].normal, b.interactions[i].normal);
  }
  EXPECT_EQ(a.time.end_time, b.time.end_time);
  EXPECT_EQ(a.time.stability_coefficient, b.time.stability_coefficient);
  EXPECT_EQ(a.time.max_steps, b.time.max_steps);
  EXPECT_EQ(a.time.min_time_step, b.time.min_time_step);
  EXPECT_EQ(a.time.wall_clock_limit, b.time.wall_clock_limit);
  EXPECT_EQ(a.time.energy_balance_limit, b.time.energy_balance_limit);
  EXPECT_EQ(a.output.snapshot_times, b.output.snapshot_times);
  EXPECT_EQ(a.output.history_interval, b.output.history_interval);
}

TEST(SceneIo, resolved_document_round_trips) {
  json axisym = axisym_scene();
  axisym["bodies"][0]["material"] = {{"base", "cu-deck"}, {"strength", {{"A", 100e6}}}};
  axisym["bodies"][0]["discretization"]["grading"] = {{"focus", {0, 0, 0}}, {"ratio", 1.2}};
  axisym["boundary_conditions"] = json::parse(R"([
    {"body": "particle", "on": "axis", "type": "symmetry", "name": "axis_set"},
    {"body": "particle", "on": "curved", "type": "velocity", "name": "driven", "components": ["z"],
     "history": {"time": [0, 1e-9, 2e-9], "velocity": [[0, 0, 0], [0, 0, -5], [1, 0, -5]],
                 "interpolation": "smooth-step"}}
  ])");
  axisym["output"] = {{"snapshot_count", 3}};
  for (const json& doc : {axisym, hex_scene()}) {
    const LoadedScene loaded = read_scene(doc);
    EXPECT_TRUE(validate("scene", loaded.resolved).empty());
    // Every default is written out and every material inlined.
    for (const json& b : loaded.resolved["bodies"]) {
      EXPECT_TRUE(b["material"].is_object());
      EXPECT_FALSE(b["material"].contains("base"));
      EXPECT_TRUE(b["initial"].contains("temperature"));
      EXPECT_TRUE(b["hourglass"].contains("coefficient"));
    }
    EXPECT_TRUE(loaded.resolved["time"].contains("stability_coefficient"));
    const LoadedScene again = read_scene(loaded.resolved);
    expect_same_scene(loaded.scene, again.scene);
    EXPECT_EQ(loaded.resolved, again.resolved);
  }
}

// The run summary (schemas/result.schema.json) lives next to the scene
// schema: what `splat run --json` prints must satisfy it.
TEST(SceneIo, run_summary_satisfies_the_result_schema) {
  RunSummary summary;
  summary.scene = "cu-particle-on-wall";
  summary.outcome = RunOutcome::timed_out;
  summary.stop_reason = StopReason::step_limit;
  summary.bodies.push_back({});
  summary.bodies[0].name = "particle";
  json doc = to_json(summary);
  EXPECT_TRUE(validate("result", doc).empty()) << listing(validate("result", doc));
  summary.hdf5_path = "out/a.h5";
  summary.xdmf_path = "out/a.xmf";
  doc = to_json(summary);
  EXPECT_TRUE(validate("result", doc).empty()) << listing(validate("result", doc));
  doc["energy"]["extra"] = 1.0;
  doc["bodies"][0].erase("mass");
  doc["outcome"] = "done";
  const std::vector<SchemaViolation> v = validate("result", doc);
  EXPECT_NE(std::find(v.begin(), v.end(), SchemaViolation{"/energy/extra", "unknown field"}),
            v.end())
      << listing(v);
  EXPECT_NE(
      std::find(v.begin(), v.end(), SchemaViolation{"/bodies/0/mass", "required field is missing"}),
      v.end())
      << listing(v);
  EXPECT_EQ(std::count_if(v.begin(), v.end(),
                          [](const SchemaViolation& x) { return x.pointer == "/outcome"; }),
            1)
      << listing(v);
}

}  // namespace
}  // namespace splat
