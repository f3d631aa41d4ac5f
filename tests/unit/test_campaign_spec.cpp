// Campaign specs (schemas/campaign.schema.json, campaign/spec.hpp): reading,
// errors that name the field, expansion into the Cartesian product, job
// identity by hash of the resolved scene, and SHA-256 itself.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "campaign/sha256.hpp"
#include "campaign/spec.hpp"
#include "solver/input/schema.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;

// The scene as given, untouched: enough to test expansion itself.
const SceneResolver identity = [](const json& scene, const std::filesystem::path&) {
  return scene;
};

json two_mass_campaign() {
  return json::parse(R"({
    "name": "tm",
    "base_scene": {"name": "tm", "two_mass": {"V0": 1.0, "adhesion": {"G_c": 0.2,
                   "sigma_c": null, "activation": {"drop_percent": 0}, "D_adh_max": null}}},
    "velocity": {"range": {"from": 0.5, "to": 1.5, "step": 0.25}},
    "G_c": {"values": [0.1, 0.2]},
    "sigma_c": {"values": [null, 2.0, 4.0]}
  })");
}

std::vector<std::string> messages(const json& doc) {
  try {
    read_campaign(doc);
  } catch (const splat::InputError& e) {
    std::vector<std::string> out;
    for (const auto& v : e.violations()) out.push_back(to_string(v));
    return out;
  }
  return {};
}

bool has(const std::vector<std::string>& v, const std::string& s) {
  for (const std::string& x : v) {
    if (x.find(s) != std::string::npos) return true;
  }
  return false;
}

TEST(campaign_sha256, matches_the_fips_180_examples) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // One million 'a' (many blocks).
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // Lengths around the padding boundary (55, 56, 64 bytes) differ from each other.
  std::set<std::string> d;
  for (std::size_t n : {55u, 56u, 63u, 64u, 65u}) d.insert(sha256_hex(std::string(n, 'x')));
  EXPECT_EQ(d.size(), 5u);
}

TEST(campaign_spec, two_mass_defaults_the_pointers) {
  const CampaignSpec s = read_campaign(two_mass_campaign());
  EXPECT_EQ(s.velocity_pointer, "/two_mass/V0");
  EXPECT_EQ(s.velocities, (std::vector<double>{0.5, 0.75, 1.0, 1.25, 1.5}));
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].pointer, "/two_mass/adhesion/G_c");
  EXPECT_EQ(s.axes[1].pointer, "/two_mass/adhesion/sigma_c");
  EXPECT_EQ(s.axes[1].unit, "Pa");
}

TEST(campaign_spec, particle_impact_defaults_the_pointers) {
  // An impact scene ends stick or rebound like a two-mass one; its axes
  // default to the fields of the particle_impact block.
  const json doc = json::parse(R"({
    "name": "impact",
    "base_scene": {"name": "impact", "particle_impact": {
      "particle": {"material": "al-thesis", "radius": 12.5e-6},
      "velocity": 400, "adhesion": {"G_c": 30, "D_adh_max": 0.5}}},
    "velocity": {"values": [300, 600]},
    "G_c": {"values": [10, 30]},
    "D_adh_max": {"values": [0.5, null]}
  })");
  const CampaignSpec s = read_campaign(doc);
  EXPECT_EQ(s.velocity_pointer, "/particle_impact/velocity");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].pointer, "/particle_impact/adhesion/G_c");
  EXPECT_EQ(s.axes[1].pointer, "/particle_impact/adhesion/D_adh_max");
  const std::vector<ExpandedJob> jobs = expand(s, identity, "v1");
  ASSERT_EQ(jobs.size(), 8u);
  EXPECT_EQ(jobs[1].scene.at("/particle_impact/velocity"_json_pointer), 600.0);
}

TEST(campaign_spec, jobs_write_no_field_snapshots_unless_the_base_scene_asks) {
  // An impact run takes field snapshots by default; a campaign job keeps
  // only its histories (no time or disk spent on fields nobody looks at).
  json doc = json::parse(R"({
    "name": "impact",
    "base_scene": {"name": "impact", "particle_impact": {
      "particle": {"material": "al-thesis", "radius": 12.5e-6, "elements_across": 4},
      "velocity": 400, "adhesion": {"G_c": 30}}},
    "velocity": {"values": [300]}
  })");
  const SceneResolver resolve = splat_scene_resolver();
  const ExpandedJob plain = expand(read_campaign(doc), resolve, "v1").at(0);
  EXPECT_EQ(plain.scene.at("/output/snapshot_times"_json_pointer), json::array());
  doc["base_scene"]["output"] = {{"snapshot_count", 2}};
  const ExpandedJob asked = expand(read_campaign(doc), resolve, "v1").at(0);
  EXPECT_EQ(asked.scene.at("/output/snapshot_times"_json_pointer).size(), 2u);
}

TEST(campaign_spec, expansion_is_the_cartesian_product) {
  const CampaignSpec s = read_campaign(two_mass_campaign());
  const std::vector<ExpandedJob> jobs = expand(s, identity, "v1");
  ASSERT_EQ(jobs.size(), 2u * 3u * 5u);
  std::set<std::string> hashes, keys;
  for (const ExpandedJob& j : jobs) {
    hashes.insert(j.hash);
    keys.insert(j.params_key);
    EXPECT_EQ(j.scene.at("/two_mass/V0"_json_pointer), j.velocity);
    EXPECT_EQ(j.scene.at("/two_mass/adhesion/G_c"_json_pointer), j.params.at("G_c"));
    EXPECT_EQ(j.scene.at("/two_mass/adhesion/sigma_c"_json_pointer), j.params.at("sigma_c"));
    EXPECT_EQ(j.hash.size(), 64u);
  }
  EXPECT_EQ(hashes.size(), jobs.size());
  EXPECT_EQ(keys.size(), 6u);
  // Velocity varies fastest, in the order given; the first set is G_c 0.1, sigma_c null.
  EXPECT_EQ(jobs[0].params, json::parse(R"({"G_c": 0.1, "sigma_c": null})"));
  EXPECT_EQ(jobs[1].velocity, 0.75);
}

TEST(campaign_spec, identity_depends_on_scene_and_solver_version_only) {
  const CampaignSpec s = read_campaign(two_mass_campaign());
  const json p = json::parse(R"({"G_c": 0.1, "sigma_c": null})");
  const ExpandedJob a = make_job(s, p, 1.0, identity, "v1");
  const ExpandedJob b = make_job(s, p, 1.0, identity, "v1");
  const ExpandedJob c = make_job(s, p, 1.0, identity, "v2");
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_NE(a.hash, c.hash);
  EXPECT_EQ(a.hash, sha256_hex(canonical_text(a.scene) + "\nv1"));
  // Another campaign (other name, other axes) producing the same scene: same job.
  json other = two_mass_campaign();
  other["name"] = "other";
  other["velocity"] = {{"values", {1.0}}};
  other.erase("sigma_c");
  other["base_scene"]["two_mass"]["adhesion"]["sigma_c"] = nullptr;
  const CampaignSpec s2 = read_campaign(other);
  const ExpandedJob d = make_job(s2, json{{"G_c", 0.1}}, 1.0, identity, "v1");
  EXPECT_EQ(a.hash, d.hash);
  EXPECT_NE(spec_hash(s), spec_hash(s2));
}

TEST(campaign_spec, identical_resolved_scenes_share_one_job) {
  // A resolver that drops a cosmetic field: two parameter sets give one scene.
  const SceneResolver drop_note = [](const json& scene, const std::filesystem::path&) {
    json out = scene;
    out.erase("note");
    return out;
  };
  json doc = two_mass_campaign();
  doc.erase("G_c");
  doc.erase("sigma_c");
  doc["base_scene"]["note"] = "";
  doc["fields"] = json::parse(R"([{"pointer": "/note", "unit": "-", "values": ["a", "b"]}])");
  const std::vector<ExpandedJob> jobs = expand(read_campaign(doc), drop_note, "v1");
  ASSERT_EQ(jobs.size(), 10u);  // 2 parameter sets x 5 velocities, all points kept
  std::set<std::string> hashes;
  for (const ExpandedJob& j : jobs) hashes.insert(j.hash);
  EXPECT_EQ(hashes.size(), 5u);  // but only 5 distinct jobs
}

TEST(campaign_spec, bad_specs_name_the_field_and_rule) {
  json d = two_mass_campaign();
  d["velocity"]["range"]["step"] = 0;
  EXPECT_TRUE(has(messages(d), "/velocity/range/step: must be > 0 (m/s)")) << messages(d)[0];

  d = two_mass_campaign();
  d["G_c"]["values"] = json::array({-1.0});
  EXPECT_TRUE(has(messages(d), "/G_c/values/0: must be >= 0 (J/m^2)"));

  d = two_mass_campaign();
  d["velocity"]["range"] = {{"from", 2.0}, {"to", 1.0}, {"step", 0.1}};
  EXPECT_TRUE(has(messages(d), "/velocity/range: must contain at least one speed"));

  d = two_mass_campaign();
  d["base_scene"] = {{"name", "fe"}, {"bodies", json::array()}};
  EXPECT_TRUE(has(messages(d), "/velocity/pointer: required unless the base scene has a two_mass"));
  EXPECT_TRUE(has(messages(d), "/G_c/pointer: required unless"));

  d = two_mass_campaign();
  d["fields"] = json::parse(R"([{"pointer": "/two_mass/V0", "unit": "m/s", "values": [1]}])");
  EXPECT_TRUE(has(messages(d), "/fields/0/pointer: pointer '/two_mass/V0' is set by another axis"));

  d = two_mass_campaign();
  d["fields"] = json::parse(R"([{"pointer": "/nowhere/x", "unit": "-", "values": [1]}])");
  EXPECT_TRUE(has(messages(d), "/fields/0/pointer: the base scene has no '/nowhere'"));

  d = two_mass_campaign();
  d["executor"] = "cloud";
  EXPECT_TRUE(has(messages(d), "/executor: must be one of"));

  d = two_mass_campaign();
  d["base_scene"] = "/no/such/scene.json";
  EXPECT_TRUE(has(messages(d), "/base_scene: "));
}

// refinement.points_per_round: 1 (bisection) unless given, read into the
// rule; out of 1-64 refused, naming the field and the rule.
TEST(campaign_spec, points_per_round_is_read_into_the_rule_or_refused) {
  json d = two_mass_campaign();
  d["refinement"] = {{"tolerance", 0.01}, {"guard_band", 0.02}};
  EXPECT_EQ(read_campaign(d).refinement->points_per_round, 1);
  d["refinement"]["points_per_round"] = 4;
  const RefinementRule rule = read_campaign(d).refinement->rule();
  EXPECT_EQ(rule.tolerance, 0.01);
  EXPECT_EQ(rule.guard_band, 0.02);
  EXPECT_EQ(rule.points_per_round, 4);
  d["refinement"]["points_per_round"] = 64;
  EXPECT_TRUE(messages(d).empty());
  d["refinement"]["points_per_round"] = 0;
  EXPECT_TRUE(has(messages(d), "/refinement/points_per_round: must be >= 1 (-)")) << messages(d)[0];
  d["refinement"]["points_per_round"] = 65;
  EXPECT_TRUE(has(messages(d), "/refinement/points_per_round: must be <= 64 (-)"))
      << messages(d)[0];
  d["refinement"]["points_per_round"] = 2.5;
  EXPECT_TRUE(has(messages(d), "/refinement/points_per_round: must be")) << messages(d)[0];
}

TEST(campaign_spec, base_scene_by_path_and_real_resolution) {
  // A real splat scene resolved by splat: defaults written out, so a job that
  // sets a field to its default is the same job as one that leaves it out.
  const std::filesystem::path scene =
      std::filesystem::path(SPLAT_SOURCE_DIR) / "scenes" / "taylor_copper_axisym.json";
  json doc = json::parse(R"({
    "name": "taylor",
    "velocity": {"pointer": "/bodies/0/initial/velocity/2", "scale": -1, "values": [100, 200]},
    "fields": [{"pointer": "/time/max_steps", "unit": "-", "values": [10000000, 500]}]
  })");
  doc["base_scene"] = scene.string();
  const CampaignSpec s = read_campaign(doc);
  const std::vector<ExpandedJob> jobs = expand(s, splat_scene_resolver(), "v1");
  ASSERT_EQ(jobs.size(), 4u);
  EXPECT_EQ(jobs[0].scene.at("/time/max_steps"_json_pointer), 10000000);
  EXPECT_EQ(jobs[1].scene.at("/bodies/0/initial/velocity/2"_json_pointer), -200.0);
  EXPECT_TRUE(jobs[0].scene.at("/bodies/0/material"_json_pointer).is_object());  // inlined

  json plain = doc;
  plain.erase("fields");
  const CampaignSpec s2 = read_campaign(plain);
  const ExpandedJob same = make_job(s2, json::object(), 100, splat_scene_resolver(), "v1");
  EXPECT_EQ(same.hash, jobs[0].hash);
  EXPECT_NE(same.hash, jobs[2].hash);

  // A value the scene rejects is an input error naming the campaign field
  // that wrote it, and the scene field.
  json bad = doc;
  bad["fields"][0]["values"] = json::array({500, -3});
  try {
    expand(read_campaign(bad), splat_scene_resolver(), "v1");
    FAIL() << "no error";
  } catch (const splat::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/fields/0/values/1: must be >= 1"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("written at /time/max_steps"), std::string::npos)
        << e.what();
  }
}

// A speed whose kinetic energy is beyond double range is named at the
// velocity that gives it, not at the scene field the campaign wrote.
TEST(campaign_spec, a_job_value_the_scene_refuses_names_the_campaign_field) {
  json d = two_mass_campaign();
  d["base_scene"]["two_mass"] = {{"M", 1.0},  {"m", 2.0},    {"k", 0.0},
                                 {"V0", 1.0}, {"area", 1.0}, {"adhesion", {{"G_c", 0.2}}}};
  d["base_scene"]["time"] = {{"end_time", 10.0}};
  d.erase("sigma_c");
  d["velocity"] = {{"values", {1.0, 1e300}}};
  try {
    expand(read_campaign(d), splat_scene_resolver(), "v1");
    FAIL() << "no error";
  } catch (const splat::InputError& e) {
    ASSERT_FALSE(e.violations().empty());
    EXPECT_EQ(e.violations()[0].pointer, "/velocity/values/1") << e.what();
    EXPECT_NE(e.violations()[0].message.find("must be finite in double precision"),
              std::string::npos)
        << e.what();
  }
}

// A range of more than 1e6 speeds is refused before anything is listed.
// (Ranges without end, whose listing would exhaust memory where the check is
// missing, are cli.a_velocity_range_without_end_is_refused_at_its_field, run
// under an address-space limit.)
TEST(campaign_spec, a_range_of_more_than_a_million_speeds_is_refused) {
  json d = two_mass_campaign();
  d["velocity"]["range"] = {{"from", 0.0}, {"to", 2e6}, {"step", 1.0}};
  EXPECT_TRUE(has(messages(d), "/velocity/range: lists more than 1e6 speeds")) << messages(d)[0];
  d["velocity"]["range"] = {{"from", 0.2}, {"to", 1.0}, {"step", 0.2}};
  EXPECT_EQ(read_campaign(d).velocities.size(), 5u);
}

}  // namespace

// Coarse to fine: the grid holds only the coarsest level of the
// elements_across ladder (the finer levels are refinement's work); without
// such an axis the option is an error naming it.
TEST(campaign_spec, coarse_to_fine_grids_the_coarsest_level_only) {
  json doc = json::parse(R"({
    "name": "ladder",
    "base_scene": {"name": "impact", "particle_impact": {
      "particle": {"material": "al-thesis", "radius": 12.5e-6, "elements_across": 8},
      "velocity": 400, "adhesion": {"G_c": 30}}},
    "velocity": {"values": [300, 600]},
    "G_c": {"values": [10, 30]},
    "fields": [{"pointer": "/particle_impact/particle/elements_across", "unit": "-",
                "values": [16, 8, 32]}],
    "refinement": {"tolerance": 10, "coarse_to_fine": true}
  })");
  const CampaignSpec s = read_campaign(doc);
  ASSERT_NE(ladder_axis(s), nullptr);
  const std::vector<ExpandedJob> jobs = expand(s, identity, "v1");
  ASSERT_EQ(jobs.size(), 4u);  // 2 G_c x 2 velocities, at 8 across only
  for (const ExpandedJob& j : jobs) {
    EXPECT_EQ(j.scene.at("/particle_impact/particle/elements_across"_json_pointer), 8);
  }
  doc["refinement"]["coarse_to_fine"] = false;
  EXPECT_EQ(expand(read_campaign(doc), identity, "v1").size(), 12u);

  doc["refinement"]["coarse_to_fine"] = true;
  doc["fields"][0]["values"] = json::array({8});
  EXPECT_TRUE(has(messages(doc),
                  "/refinement/coarse_to_fine: needs a `fields` axis on "
                  "/particle_impact/particle/elements_across"))
      << messages(doc).size();
}
