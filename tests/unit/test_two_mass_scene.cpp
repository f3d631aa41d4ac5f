// Two-mass scenes and the adhesion block (schemas/scene.schema.json
// #/definitions/adhesion): parsing, defaults, round trip of the resolved
// document, and every bad input reported at its pointer with its rule.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/core/run_summary.hpp"
#include "solver/input/adhesion_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/two_mass/two_mass_model.hpp"

namespace splat {
namespace {

using nlohmann::json;

json two_mass_scene() {
  return json::parse(R"({
    "name": "tm",
    "two_mass": {"M": 1, "m": 2, "k": 0.5, "V0": 1, "area": 1,
                 "adhesion": {"G_c": 0.2, "sigma_c": 0.5}},
    "time": {"end_time": 50, "dt": 1e-3}
  })");
}

std::vector<SchemaViolation> violations_of(const json& doc) {
  try {
    read_scene(doc);
  } catch (const InputError& e) {
    return e.violations();
  }
  return {};
}

void expect_violation(const json& doc, const std::string& pointer, const std::string& words) {
  const std::vector<SchemaViolation> v = violations_of(doc);
  bool found = false;
  std::string listing;
  for (const SchemaViolation& x : v) {
    found |= x.pointer == pointer && x.message.find(words) != std::string::npos;
    listing += "\n  " + to_string(x);
  }
  EXPECT_TRUE(found) << "expected " << pointer << ": ..." << words << "...; got" << listing;
}

TEST(two_mass_scene, parses_with_defaults) {
  const Scene s = read_scene(two_mass_scene()).scene;
  ASSERT_TRUE(s.two_mass.has_value());
  EXPECT_TRUE(s.bodies.empty());
  const TwoMassSpec& t = *s.two_mass;
  EXPECT_EQ(t.M, 1.0);
  EXPECT_EQ(t.m, 2.0);
  EXPECT_EQ(t.k, 0.5);
  EXPECT_EQ(t.V0, 1.0);
  EXPECT_EQ(t.area, 1.0);
  EXPECT_EQ(t.adhesion.G_c, 0.2);
  EXPECT_EQ(t.adhesion.sigma_c, 0.5);
  EXPECT_EQ(t.adhesion.activation, ActivationRule::none);
  EXPECT_FALSE(t.adhesion.D_adh_max.has_value());
  EXPECT_EQ(s.time.dt, 1e-3);
}

TEST(two_mass_scene, the_verification_scene_reads) {
  const LoadedScene l =
      load_scene(std::string(SPLAT_SOURCE_DIR) + "/scenes/verification/two_mass.json");
  ASSERT_TRUE(l.scene.two_mass.has_value());
  EXPECT_EQ(l.scene.two_mass->adhesion.G_c * l.scene.two_mass->area, 0.2);
  EXPECT_FALSE(l.scene.description.empty());
}

TEST(two_mass_scene, resolved_document_round_trips) {
  json doc = two_mass_scene();
  doc["two_mass"]["adhesion"]["sigma_c"] = nullptr;
  doc["two_mass"]["adhesion"]["D_adh_max"] = 0.7;
  const LoadedScene a = read_scene(doc);
  EXPECT_TRUE(validate("scene", a.resolved).empty());
  EXPECT_TRUE(a.resolved["two_mass"]["adhesion"]["sigma_c"].is_null());
  const LoadedScene b = read_scene(a.resolved);
  EXPECT_EQ(a.resolved, b.resolved);
  EXPECT_FALSE(b.scene.two_mass->adhesion.sigma_c.has_value());
  EXPECT_EQ(b.scene.two_mass->adhesion.D_adh_max, 0.7);
  EXPECT_EQ(b.scene.time.dt, 1e-3);
  EXPECT_FALSE(a.resolved.contains("bodies"));
}

TEST(two_mass_scene, adhesion_block_round_trips_every_field) {
  const json j = json::parse(R"({"G_c": 30, "sigma_c": 1.5e9,
      "activation": {"rule": "yield-drop", "drop_percent": 25, "sides": "both"},
      "D_adh_max": 0.5})");
  const AdhesionParams p = adhesion_from_json(j);
  EXPECT_EQ(p.G_c, 30.0);
  EXPECT_EQ(p.sigma_c, 1.5e9);
  EXPECT_EQ(p.activation, ActivationRule::yield_drop);
  EXPECT_DOUBLE_EQ(p.yield_drop, 0.25);
  EXPECT_EQ(p.sides, ActivationSides::both);
  EXPECT_EQ(p.D_adh_max, 0.5);
  const AdhesionParams q = adhesion_from_json(adhesion_to_json(p));
  EXPECT_EQ(q.G_c, p.G_c);
  EXPECT_EQ(q.sigma_c, p.sigma_c);
  EXPECT_EQ(q.activation, p.activation);
  EXPECT_DOUBLE_EQ(q.yield_drop, p.yield_drop);
  EXPECT_EQ(q.sides, p.sides);
  EXPECT_EQ(q.D_adh_max, p.D_adh_max);
  const AdhesionParams f = adhesion_from_json(json::parse(R"({"G_c": 30,
      "activation": {"rule": "surface-expansion", "surface_expansion": 0.4,
                     "bonded_fraction": "film-cracks"}})"));
  EXPECT_EQ(f.bonded_fraction, BondedFraction::film_cracks);
  EXPECT_EQ(adhesion_from_json(adhesion_to_json(f)).bonded_fraction, BondedFraction::film_cracks);
  EXPECT_EQ(adhesion_from_json(adhesion_to_json(f)).surface_expansion, 0.4);
  // The surface-expansion rule bonds the film cracks unless told full; the
  // other rules bond whole links.
  const AdhesionParams cracks = adhesion_from_json(json::parse(
      R"({"G_c": 30, "activation": {"rule": "surface-expansion", "surface_expansion": 0.4}})"));
  EXPECT_EQ(cracks.bonded_fraction, BondedFraction::film_cracks);
  const AdhesionParams whole = adhesion_from_json(json::parse(R"({"G_c": 30,
      "activation": {"rule": "surface-expansion", "surface_expansion": 0.4,
                     "bonded_fraction": "full"}})"));
  EXPECT_EQ(whole.bonded_fraction, BondedFraction::full);
  EXPECT_EQ(adhesion_from_json(adhesion_to_json(whole)).bonded_fraction, BondedFraction::full);
  // Defaults: no cap, no activation rule, never eroded.
  const AdhesionParams d = adhesion_from_json(json{{"G_c", 1.0}});
  EXPECT_FALSE(d.sigma_c.has_value());
  EXPECT_EQ(d.activation, ActivationRule::none);
  EXPECT_FALSE(d.D_adh_max.has_value());
  EXPECT_EQ(d.bonded_fraction, BondedFraction::full);
}

TEST(two_mass_scene, bad_inputs_name_the_field_and_the_rule) {
  json doc = two_mass_scene();
  doc["two_mass"]["adhesion"]["G_c"] = -1;
  expect_violation(doc, "/two_mass/adhesion/G_c", "must be >= 0 (J/m^2)");

  doc = two_mass_scene();
  doc["two_mass"]["adhesion"]["activation"] = {{"rule", "yield-drop"}};
  expect_violation(doc, "/two_mass/adhesion/activation/drop_percent", "required");

  doc["two_mass"]["adhesion"]["activation"]["drop_percent"] = 100;
  expect_violation(doc, "/two_mass/adhesion/activation/drop_percent", "must be < 100 (%)");

  doc["two_mass"]["adhesion"]["activation"]["drop_percent"] = 30;
  expect_violation(doc, "/two_mass/adhesion/activation/rule", "no yield stress");

  // The films crack on the surface expansion: film-cracks reads no other rule.
  doc["two_mass"]["adhesion"]["activation"]["bonded_fraction"] = "film-cracks";
  expect_violation(doc, "/two_mass/adhesion/activation/rule", "must be \"surface-expansion\"");

  doc = two_mass_scene();
  doc["two_mass"]["adhesion"]["D_adh_max"] = 1.5;
  expect_violation(doc, "/two_mass/adhesion/D_adh_max", "must be <= 1 (-)");

  doc = two_mass_scene();
  doc["two_mass"]["k"] = -1;
  expect_violation(doc, "/two_mass/k", "must be >= 0 (N/m)");

  // Issue 28 item 11: V0 = 1e300 ran with infinite energies, printed them as
  // null and exited 0.
  doc = two_mass_scene();
  doc["two_mass"]["V0"] = 1e300;
  expect_violation(doc, "/two_mass/V0", "must be finite in double precision (J)");

  doc = two_mass_scene();
  doc["two_mass"].erase("area");
  expect_violation(doc, "/two_mass/area", "required field is missing");

  doc = two_mass_scene();
  doc["time"]["dt"] = 4.0;  // 2 sqrt(m / k) = 4 s
  expect_violation(doc, "/time/dt", "must be < 2 sqrt(m / k)");

  doc = two_mass_scene();
  doc["time"]["dt"] = 60.0;
  doc["two_mass"]["k"] = 0.0;
  expect_violation(doc, "/time/dt", "must be <= end_time (s)");

  doc = two_mass_scene();
  doc["boundary_conditions"] = json::array();
  expect_violation(doc, "/boundary_conditions", "a two_mass scene has no boundary_conditions");

  doc = two_mass_scene();
  doc["output"] = {{"snapshot_count", 3}};
  expect_violation(doc, "/output", "a two_mass scene has no field snapshots");

  doc = two_mass_scene();
  doc.erase("two_mass");
  expect_violation(doc, "/bodies", "required field is missing");
}

TEST(two_mass_scene, fe_scenes_take_no_fixed_time_step) {
  json doc = json::parse(R"({
    "name": "fe",
    "bodies": [{"name": "p", "material": "cu-deck",
                "geometry": {"type": "half-disc", "radius": 1e-5, "z_centre": 1e-5},
                "discretization": {"type": "fe-axisym", "elements_across": 4}}],
    "time": {"end_time": 1e-8, "dt": 1e-10}
  })");
  expect_violation(doc, "/time/dt", "only two_mass scenes take a fixed time step");
  doc["time"].erase("dt");
  EXPECT_TRUE(violations_of(doc).empty());
  EXPECT_FALSE(read_scene(doc).resolved["time"].contains("dt"));
}

TEST(two_mass_scene, summary_satisfies_the_result_schema) {
  const Scene s = read_scene(two_mass_scene()).scene;
  SimulationOptions o;  // no output folder: no file
  const RunSummary r = run_two_mass(s, read_scene(two_mass_scene()).resolved, o);
  EXPECT_EQ(r.outcome, RunOutcome::rebound) << r.reason;
  const json doc = to_json(r);
  EXPECT_TRUE(validate("result", doc).empty()) << doc.dump(2);
  EXPECT_TRUE(doc["separation_velocity"].is_number());
  EXPECT_TRUE(doc["output"]["hdf5"].is_null());
}

}  // namespace
}  // namespace splat
