// Material documents to Material and back: the library loads with the
// numbers of its sources, round trips are exact, the checks a schema cannot
// express name their pointer and unit, and names and paths resolve.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/input/schema.hpp"

namespace splat {

namespace {

using nlohmann::json;
using Violations = std::vector<SchemaViolation>;

json with(json doc, const std::string& pointer, const json& value) {
  doc[json::json_pointer(pointer)] = value;
  return doc;
}

// The violations material_from_json throws with (empty if it does not).
Violations rejection(const json& doc) {
  try {
    material_from_json(doc);
  } catch (const InputError& e) {
    return e.violations();
  }
  return {};
}

void expect_same(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.elastic.E, b.elastic.E);
  EXPECT_EQ(a.elastic.nu, b.elastic.nu);
  // Every parameter of the law, whichever it is.
  ASSERT_EQ(a.strength.index(), b.strength.index());
  std::visit(
      [&](const auto& s) {
        const auto& t = std::get<std::decay_t<decltype(s)>>(b.strength);
        for (const auto& f : s.fields()) EXPECT_EQ(s.*f.member, t.*f.member) << f.name;
      },
      a.strength);
  EXPECT_EQ(a.thermal.c_p, b.thermal.c_p);
  EXPECT_EQ(a.thermal.heat_fraction, b.thermal.heat_fraction);
  EXPECT_EQ(a.eos.model, b.eos.model);
  ASSERT_EQ(a.eos.mie_gruneisen.has_value(), b.eos.mie_gruneisen.has_value());
  if (a.eos.mie_gruneisen) {
    EXPECT_EQ(a.eos.mie_gruneisen->c0, b.eos.mie_gruneisen->c0);
    EXPECT_EQ(a.eos.mie_gruneisen->s, b.eos.mie_gruneisen->s);
    EXPECT_EQ(a.eos.mie_gruneisen->gamma0, b.eos.mie_gruneisen->gamma0);
  }
  const DamageParams &d = a.damage, &e = b.damage;
  EXPECT_EQ(d.initiation, e.initiation);
  EXPECT_EQ(d.jc.D1, e.jc.D1);
  EXPECT_EQ(d.jc.D2, e.jc.D2);
  EXPECT_EQ(d.jc.D3, e.jc.D3);
  EXPECT_EQ(d.jc.D4, e.jc.D4);
  EXPECT_EQ(d.jc.D5, e.jc.D5);
  EXPECT_EQ(d.shear.k_s, e.shear.k_s);
  EXPECT_EQ(d.shear.theta_min, e.shear.theta_min);
  EXPECT_EQ(d.shear.theta_max, e.shear.theta_max);
  EXPECT_EQ(d.shear.rate_low, e.shear.rate_low);
  EXPECT_EQ(d.shear.rate_high, e.shear.rate_high);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(d.shear.low[i], e.shear.low[i]);
    EXPECT_EQ(d.shear.high[i], e.shear.high[i]);
  }
  EXPECT_EQ(d.evolution, e.evolution);
  EXPECT_EQ(d.eps_p_max, e.eps_p_max);
  EXPECT_EQ(d.G_f, e.G_f);
  EXPECT_EQ(d.D_max, e.D_max);
  EXPECT_EQ(d.initial_random_max, e.initial_random_max);
}

TEST(material_library, every_material_loads_under_its_own_name) {
  for (const std::string& name : material_names()) {
    const Material m = load_material(name);
    EXPECT_EQ(m.name, name);
    EXPECT_FALSE(m.source.empty());
    EXPECT_EQ(m.eos.model, EosModel::linear) << name << ": the thesis uses a linear EOS";
    // No Hugoniot was read for these alloys (their sources say so).
    const bool no_hugoniot = name == "ti6al4v-jc" || name == "ni200-jc" || name == "ss316l-jc" ||
                             name == "in718-jc" || name == "fe-armco-jc" || name == "ta-ptw" ||
                             name == "al1100-o-jc";
    EXPECT_EQ(m.eos.mie_gruneisen.has_value(), !no_hugoniot) << name;
  }
}

TEST(material_library, aluminium_of_the_thesis_tables) {
  const Material m = load_material("al-thesis");
  EXPECT_EQ(m.density, 2710.0);
  EXPECT_EQ(m.elastic.E, 70.9e9);
  EXPECT_EQ(m.elastic.nu, 0.3);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).A, 148.4e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).B, 345.5e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).n, 0.183);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).C, 0.001);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).m, 0.895);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).T_melt, 916.0);
  EXPECT_EQ(m.thermal.c_p, 904.0);
  EXPECT_EQ(m.damage.initiation, DamageInitiation::shear);
  EXPECT_EQ(m.damage.shear.k_s, 0.3);
  EXPECT_EQ(m.damage.shear.theta_min, 1.42);
  EXPECT_EQ(m.damage.shear.theta_max, 2.2);
  EXPECT_EQ(m.damage.shear.rate_low, 0.001);
  EXPECT_EQ(m.damage.shear.rate_high, 250.0);
  EXPECT_EQ(m.damage.shear.low[0], 4.391);
  EXPECT_EQ(m.damage.shear.low[3], -14.39);
  EXPECT_EQ(m.damage.shear.high[0], 0.0);
  EXPECT_EQ(m.damage.shear.high[3], 2.466);
  EXPECT_EQ(m.damage.evolution, DamageEvolution::plastic_strain);
  EXPECT_EQ(m.damage.eps_p_max, 2.0);
  EXPECT_EQ(m.damage.D_max, 0.9);
  EXPECT_EQ(m.damage.initial_random_max, 0.001);
}

TEST(material_library, deck_sets_differ_from_the_tables_where_the_deck_says_so) {
  const Material al = load_material("al-deck");
  EXPECT_EQ(al.elastic.E, 70.2e9);
  EXPECT_EQ(std::get<JohnsonCookParams>(al.strength).A, 60e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(al.strength).B, 140e6);
  EXPECT_EQ(al.damage.initial_random_max, 1e-4);
  EXPECT_EQ(std::get<JohnsonCookParams>(al.strength).m,
            std::get<JohnsonCookParams>(load_material("al-thesis").strength).m);
  const Material cu = load_material("cu-deck");
  EXPECT_EQ(std::get<JohnsonCookParams>(cu.strength).A, 160e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(cu.strength).B, 150e6);
  EXPECT_EQ(cu.damage.initial_random_max, 1e-4);
  EXPECT_EQ(cu.thermal.c_p, 385.0);
  EXPECT_EQ(std::get<JohnsonCookParams>(cu.strength).T_melt, 1356.0);
  EXPECT_EQ(cu.damage.jc.D3, -3.03);
}

TEST(material_library, copper_has_unswapped_heat_capacity_and_melting_point) {
  const Material m = load_material("cu-thesis");
  EXPECT_EQ(m.thermal.c_p, 385.0);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).T_melt, 1356.0);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).A, 90e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).B, 292e6);
  EXPECT_EQ(m.damage.initiation, DamageInitiation::johnson_cook);
  EXPECT_EQ(m.damage.jc.D1, 0.3);
  EXPECT_EQ(m.damage.jc.D2, 0.28);
  EXPECT_LT(m.damage.jc.D3, 0.0);
  EXPECT_EQ(m.damage.jc.D3, -3.03);
  EXPECT_EQ(m.damage.jc.D4, 0.014);
  EXPECT_EQ(m.damage.jc.D5, 1.12);
}

TEST(material_library, hopkinson_steel_and_ti6al4v) {
  const Material st = load_material("steel-hopkinson");
  EXPECT_EQ(st.thermal.heat_fraction, 0.8);
  EXPECT_EQ(std::get<JohnsonCookParams>(st.strength).T_ref, 293.15);
  EXPECT_EQ(std::get<JohnsonCookParams>(st.strength).A, 266e6);
  EXPECT_EQ(st.damage.initiation, DamageInitiation::none);
  EXPECT_EQ(st.damage.initial_random_max, 0.0);
  const Material ti = load_material("ti6al4v-thesis");
  EXPECT_EQ(std::get<JohnsonCookParams>(ti.strength).A, 860e6);
  EXPECT_EQ(std::get<JohnsonCookParams>(ti.strength).B, 900e6);
  EXPECT_EQ(ti.thermal.c_p, 526.3);
  EXPECT_EQ(ti.damage.jc.D1, -0.09);
  EXPECT_EQ(ti.damage.jc.D3, -0.5);
  EXPECT_EQ(ti.damage.jc.D5, 3.87);
}

// Order-of-magnitude checks that catch a wrong unit (MPa for Pa, C for K)
// or a swapped pair, and the Steinberg Hugoniot intercept against the bulk
// sound speed of the elastic constants.
TEST(material_library, numbers_make_physical_sense) {
  for (const std::string& name : material_names()) {
    SCOPED_TRACE(name);
    const Material m = load_material(name);
    EXPECT_GT(m.density, 1000.0);
    EXPECT_LT(m.density, 25000.0);
    EXPECT_GT(m.elastic.E, 10e9);
    EXPECT_LT(m.elastic.E, 500e9);
    const StrengthReferences ref = strength_references(m.strength);
    EXPECT_GT(initial_yield_stress(m.strength), 5e6);  // annealed copper, PTW: 2 G y0 = 9 MPa
    EXPECT_LT(flow_stress(m.strength, ModelSwitches{}, 1.0, ref.eps_dot_0, ref.T_ref).value, 5e9);
    EXPECT_GT(m.thermal.c_p, 100.0);
    EXPECT_LT(m.thermal.c_p, 2000.0);
    EXPECT_GT(ref.T_melt, 600.0);
    EXPECT_LT(ref.T_melt, 4000.0);
    // Room temperature: 273 K (fe-armco-jc, as its quoted table) to 310 K.
    EXPECT_GE(ref.T_ref, 273.0);
    EXPECT_LE(ref.T_ref, 310.0);
    if (m.eos.mie_gruneisen) {
      const double bulk_sound_speed = std::sqrt(m.elastic.bulk_modulus() / m.density);
      EXPECT_NEAR(m.eos.mie_gruneisen->c0 / bulk_sound_speed, 1.0, 0.2);
    }
    if (m.damage.initiation == DamageInitiation::johnson_cook) {
      // Positive failure strain without triaxiality, falling as it rises.
      EXPECT_GT(m.damage.jc.D1 + m.damage.jc.D2, 0.0);
      EXPECT_LT(m.damage.jc.D3, 0.0);
    }
    if (m.damage.initiation == DamageInitiation::shear) {
      const ShearFailureParams& s = m.damage.shear;
      for (int i = 0; i <= 20; ++i) {
        const double th = s.theta_min + (s.theta_max - s.theta_min) * i / 20.0;
        for (const double* c : {s.low, s.high}) {
          EXPECT_GT(((c[0] * th + c[1]) * th + c[2]) * th + c[3], 0.0) << "theta " << th;
        }
      }
    }
  }
}

TEST(material_round_trip, library_materials_survive_json_and_back) {
  for (const std::string& name : material_names()) {
    SCOPED_TRACE(name);
    const Material first = load_material(name);
    const json written = material_to_json(first);
    EXPECT_EQ(validate("material", written), Violations{});
    const Material second = material_from_json(written);
    expect_same(first, second);
    EXPECT_EQ(material_to_json(second), written);
  }
}

TEST(material_round_trip, other_model_choices_survive_json_and_back) {
  Material m = load_material("cu-thesis");
  m.eos.model = EosModel::mie_gruneisen;
  m.damage.evolution = DamageEvolution::fracture_energy;
  m.damage.G_f = 1.5e4;
  m.damage.D_max = 0.99;
  expect_same(m, material_from_json(material_to_json(m)));

  Material random_only = load_material("steel-hopkinson");
  random_only.damage.evolution = DamageEvolution::instant;
  random_only.damage.initial_random_max = 0.01;
  random_only.eos.mie_gruneisen.reset();
  const json j = material_to_json(random_only);
  EXPECT_EQ(j.at("damage").at("initiation"), json({{"model", "none"}}));
  EXPECT_FALSE(j.at("eos").contains("mie_gruneisen"));
  expect_same(random_only, material_from_json(j));

  // No damage block at all for a material without damage.
  EXPECT_FALSE(material_to_json(load_material("steel-hopkinson")).contains("damage"));
}

TEST(material_defaults, optional_fields_take_the_documented_defaults) {
  json doc = material_document("al-thesis");
  doc["thermal"].erase("heat_fraction");
  doc["damage"].erase("D_max");
  doc["damage"].erase("initial_random_max");
  const Material m = material_from_json(doc);
  EXPECT_EQ(m.thermal.heat_fraction, 0.9);
  EXPECT_EQ(m.damage.D_max, 0.9);
  EXPECT_EQ(m.damage.initial_random_max, 0.0);
  doc.erase("damage");
  EXPECT_EQ(material_from_json(doc).damage.initiation, DamageInitiation::none);
}

TEST(material_checks, melting_point_must_exceed_reference_temperature) {
  const json doc = with(material_document("cu-thesis"), "/strength/T_melt", 300.0);
  EXPECT_EQ(rejection(doc), (Violations{{"/strength/T_melt", "must be > T_ref (K)"}}));
  EXPECT_EQ(material_violations(doc), rejection(doc));
}

TEST(material_checks, initial_random_damage_must_not_exceed_d_max) {
  const json doc = with(material_document("al-thesis"), "/damage/initial_random_max", 0.95);
  EXPECT_EQ(rejection(doc), (Violations{{"/damage/initial_random_max", "must be <= D_max (-)"}}));
  // Against the default D_max when the document leaves it out.
  json no_cap = with(material_document("al-thesis"), "/damage/initial_random_max", 0.91);
  no_cap["damage"].erase("D_max");
  EXPECT_EQ(rejection(no_cap),
            (Violations{{"/damage/initial_random_max", "must be <= D_max (-)"}}));
}

TEST(material_checks, shear_bounds_must_be_increasing) {
  const json theta = with(material_document("al-deck"), "/damage/initiation/theta_max", 1.42);
  EXPECT_EQ(rejection(theta),
            (Violations{{"/damage/initiation/theta_max", "must be > theta_min (-)"}}));
  const json rate = with(material_document("al-deck"), "/damage/initiation/rate_low", 250.0);
  EXPECT_EQ(rejection(rate),
            (Violations{{"/damage/initiation/rate_high", "must be > rate_low (1/s)"}}));
}

TEST(material_checks, mie_gruneisen_model_without_parameters_is_rejected) {
  json doc = material_document("ti6al4v-thesis");
  doc["eos"] = {{"model", "mie-gruneisen"}};
  EXPECT_EQ(rejection(doc), (Violations{{"/eos/mie_gruneisen", "required field is missing"}}));
}

TEST(material_checks, schema_and_semantic_faults_are_reported_together) {
  json doc = with(material_document("cu-thesis"), "/strength/T_melt", 250.0);
  doc["strength"]["A"] = -1.0;
  EXPECT_EQ(rejection(doc),
            (Violations{{"/strength/A", "must be >= 0 (Pa)"},
                        {"/strength/T_melt", "must be > T_ref (K)"},
                        {"/strength/T_melt",
                         "250 K is outside what metals have (300 K to 4500 K); if it was meant "
                         "in degrees Celsius, write 523.15"}}));
  // A field the schema rejected is not blamed twice.
  doc = with(material_document("cu-thesis"), "/strength/T_melt", -1.0);
  EXPECT_EQ(rejection(doc), (Violations{{"/strength/T_melt", "must be > 0 (K)"}}));
}

TEST(material_checks, conductivity_outside_what_metals_have_is_refused) {
  const json doc = with(material_document("al-thesis"), "/thermal/conductivity", 0.237);
  EXPECT_EQ(rejection(doc),
            (Violations{{"/thermal/conductivity",
                         "0.237 W/(m K) is outside what metals have (1 to 1000 W/(m K))"}}));
}

TEST(material_lookup, unknown_name_lists_the_library) {
  try {
    load_material("unobtainium");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(
        e.violations(),
        (Violations{{"",
                     "unknown material 'unobtainium' (known: ag-sg, al-deck, al-thesis, "
                     "al-thesis-gf, al1100-o-jc, al6061-t6-jc, cu-deck, cu-ofhc-jc, cu-ofhc-ptw, "
                     "cu-thesis, fe-armco-jc, in718-jc, mg-az31b-sg, ni200-jc, ss316l-jc, "
                     "steel-hopkinson, ta-ptw, ti6al4v-jc, ti6al4v-thesis, zn-sg; or give "
                     "a path to a JSON file)"}}));
  }
}

TEST(material_lookup, files_load_and_their_faults_are_reported) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "splat_material_io";
  std::filesystem::create_directories(dir);
  const std::filesystem::path good = dir / "my-copper.json";
  json doc = material_document("cu-thesis");
  doc["name"] = "my-copper";
  doc["strength"]["A"] = 100e6;
  std::ofstream(good) << doc.dump(2);
  const Material m = load_material(good.string());
  EXPECT_EQ(m.name, "my-copper");
  EXPECT_EQ(std::get<JohnsonCookParams>(m.strength).A, 100e6);

  const std::filesystem::path bad = dir / "bad.json";
  std::ofstream(bad) << with(doc, "/elastic/nu", 0.5).dump(2);
  try {
    load_material(bad.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.violations(), (Violations{{"/elastic/nu", "must be < 0.5 (-)"}}));
  }
  try {
    load_material((dir / "absent.json").string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace splat
