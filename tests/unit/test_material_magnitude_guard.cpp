// The magnitude guard of material documents (solver/input/material_io.cpp):
// values a metal cannot have are refused, naming the field and the unit the
// value was most likely written in.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "solver/input/material_io.hpp"

namespace splat {
namespace {

using nlohmann::json;

// The one violation of `doc` at `pointer`, or "" when there is none.
std::string message_at(const json& doc, const std::string& pointer) {
  for (const SchemaViolation& v : material_violations(doc)) {
    if (v.pointer == pointer) return v.message;
  }
  return "";
}

TEST(material_magnitude_guard, library_materials_pass) {
  for (const std::string& name : material_names()) {
    EXPECT_EQ(material_violations(material_document(name)), std::vector<SchemaViolation>{}) << name;
  }
}

// "A": 163 (MPa meant, Pa written) passes the schema (A >= 0) but not the
// guard, which names /strength/A and the MPa reading.
TEST(material_magnitude_guard, yield_stress_in_mpa_is_refused_naming_the_field) {
  json doc = material_document("cu-thesis");
  doc["strength"]["A"] = 163;
  EXPECT_EQ(validate("material", doc), std::vector<SchemaViolation>{});
  const std::string m = message_at(doc, "/strength/A");
  EXPECT_NE(m.find("outside what metals have"), std::string::npos) << m;
  EXPECT_NE(m.find("MPa"), std::string::npos) << m;
  EXPECT_NE(m.find("1.63e+08"), std::string::npos) << m;
  EXPECT_THROW(material_from_json(doc), InputError);
}

TEST(material_magnitude_guard, every_law_and_every_guarded_field) {
  json za =
      material_document(std::string(SPLAT_SOURCE_DIR) + "/tests/data/za_test_parameters.json");
  za["strength"]["C0"] = 46.5;  // MPa
  EXPECT_NE(message_at(za, "/strength/C0").find("MPa"), std::string::npos);
  za["strength"]["C0"] = 46.5e6;
  za["strength"]["C2"] = 8.9e15;  // MPa converted twice
  EXPECT_NE(message_at(za, "/strength/C2").find("twice"), std::string::npos);

  json ptw = material_document("cu-ofhc-ptw");
  ptw["strength"]["M"] = 63.546;    // g/mol
  ptw["strength"]["G"] = 45.78;     // GPa
  ptw["strength"]["rho"] = 8.9375;  // g/cm^3
  EXPECT_NE(message_at(ptw, "/strength/M").find("g/mol"), std::string::npos);
  EXPECT_NE(message_at(ptw, "/strength/G").find("GPa"), std::string::npos);
  EXPECT_NE(message_at(ptw, "/strength/rho").find("g/cm^3"), std::string::npos);

  json cu = material_document("cu-thesis");
  cu["density"] = 8.96;            // g/cm^3
  cu["elastic"]["E"] = 124.0;      // GPa
  cu["thermal"]["c_p"] = 0.385;    // kJ/(kg K)
  cu["strength"]["T_ref"] = 27.0;  // degrees Celsius
  cu["strength"]["T_melt"] = 5000.0;
  EXPECT_NE(message_at(cu, "/density").find("g/cm^3"), std::string::npos);
  EXPECT_NE(message_at(cu, "/elastic/E").find("GPa"), std::string::npos);
  EXPECT_NE(message_at(cu, "/thermal/c_p").find("kJ/(kg K)"), std::string::npos);
  EXPECT_NE(message_at(cu, "/strength/T_ref").find("Celsius"), std::string::npos);
  EXPECT_NE(message_at(cu, "/strength/T_melt").find("300 K to 4500 K"), std::string::npos);

  // Steinberg's A as his tables print it (per Mbar), and per GPa; 0 (no
  // pressure term) is accepted.
  json zn = material_document("zn-sg");
  zn["strength"]["A"] = 5.95;
  EXPECT_NE(message_at(zn, "/strength/A").find("1/Mbar, write 5.95e-11"), std::string::npos)
      << message_at(zn, "/strength/A");
  zn["strength"]["A"] = 0.0595;
  EXPECT_NE(message_at(zn, "/strength/A").find("1/GPa, write 5.95e-11"), std::string::npos)
      << message_at(zn, "/strength/A");
  zn["strength"]["A"] = 0.0;
  EXPECT_EQ(message_at(zn, "/strength/A"), "");
}

// The bounds themselves are accepted, and a hardening stress may be 0
// (perfect plasticity); an initial yield stress may not.
TEST(material_magnitude_guard, bounds_and_zero_hardening_are_accepted) {
  json doc = material_document("cu-thesis");
  doc["strength"]["A"] = 1e6;
  doc["strength"]["B"] = 0.0;
  doc["density"] = 25000.0;
  doc["elastic"]["E"] = 1e9;
  EXPECT_EQ(material_violations(doc), std::vector<SchemaViolation>{});
  doc["strength"]["A"] = 0.0;
  EXPECT_NE(message_at(doc, "/strength/A"), "");
}

}  // namespace
}  // namespace splat
