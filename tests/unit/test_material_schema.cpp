// The material schema and the translation of valijson's reports: every
// shipped material is valid, every numeric field states its unit and bounds,
// and each kind of bad document gives exactly one line naming the pointer,
// the rule and the unit. The generic machinery (schema.hpp) is also checked
// on small inline schemas: $ref, oneOf dispatch on a "model" const, arrays.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/input/schema.hpp"

namespace splat {

namespace {

using nlohmann::json;
using Violations = std::vector<SchemaViolation>;

json library(const std::string& name) {
  return material_document(name);
}

// `doc` with the value at `pointer` replaced.
json with(json doc, const std::string& pointer, const json& value) {
  doc[json::json_pointer(pointer)] = value;
  return doc;
}

json without(json doc, const std::string& pointer) {
  const json::json_pointer p(pointer);
  doc.at(p.parent_pointer()).erase(p.back());
  return doc;
}

Violations check(const json& doc) {
  return validate("material", doc);
}

std::string type_of(const json& node) {
  const auto t = node.find("type");
  return t != node.end() && t->is_string() ? t->get<std::string>() : std::string();
}

bool is_closed(const json& node) {
  const auto a = node.find("additionalProperties");
  return a != node.end() && *a == false;
}

TEST(material_schema, every_library_material_is_valid) {
  const std::vector<std::string> names = material_names();
  EXPECT_EQ(names,
            (std::vector<std::string>{
                "ag-sg",           "al-deck",  "al-thesis",   "al-thesis-gf",   "al1100-o-jc",
                "al6061-t6-jc",    "cu-deck",  "cu-ofhc-jc",  "cu-ofhc-ptw",    "cu-thesis",
                "fe-armco-jc",     "in718-jc", "mg-az31b-sg", "ni200-jc",       "ss316l-jc",
                "steel-hopkinson", "ta-ptw",   "ti6al4v-jc",  "ti6al4v-thesis", "zn-sg"}));
  for (const std::string& name : names) {
    const json doc = library(name);
    EXPECT_EQ(check(doc), Violations{}) << name;
    EXPECT_EQ(doc.at("name"), name) << "library file name and document name differ";
    EXPECT_GT(doc.at("source").get<std::string>().size(), 80u) << name << ": source too vague";
  }
}

// Walks the schema: every number (or array of numbers) carries a
// description, a unit and at least one bound; every object with properties
// is closed, itself or through each of its if/then branches.
void check_node(const json& root, const json& node, const std::string& where) {
  if (!node.is_object()) return;
  if (node.contains("$ref")) return;  // checked where the definition is walked
  const std::string type = type_of(node);
  const bool numeric = type == "number" || type == "integer" || type == "array";
  if (numeric && !node.contains("const")) {
    EXPECT_TRUE(node.contains("description")) << where;
    EXPECT_TRUE(node.contains("unit")) << where;
    const json& bounded = type == "array" ? node.at("items") : node;
    const bool has_bound = bounded.contains("minimum") || bounded.contains("exclusiveMinimum") ||
                           bounded.contains("maximum") || bounded.contains("exclusiveMaximum");
    EXPECT_TRUE(has_bound) << where;
  }
  if (type == "string" && !node.contains("const")) {
    EXPECT_TRUE(node.contains("description") || node.contains("enum")) << where;
  }
  if (node.contains("properties")) {
    bool closed = is_closed(node);
    if (!closed && node.contains("allOf")) {
      closed = true;
      for (const json& branch : node.at("allOf")) {
        const json& then = branch.at("then");
        const json& target =
            then.contains("$ref")
                ? root.at(json::json_pointer(then.at("$ref").get<std::string>().substr(1)))
                : then;
        closed = closed && is_closed(target);
      }
    }
    EXPECT_TRUE(closed) << where << " accepts unknown fields";
    for (const auto& [key, sub] : node.at("properties").items()) {
      check_node(root, sub, where + "/properties/" + key);
    }
  }
  if (node.contains("items")) check_node(root, node.at("items"), where + "/items");
}

TEST(material_schema, every_number_has_description_unit_and_bounds) {
  const json& schema = schema_document("material");
  EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
  check_node(schema, schema, "");
  for (const auto& [key, def] : schema.at("definitions").items()) {
    check_node(schema, def, "/definitions/" + key);
  }
}

TEST(material_schema, schema_defaults_equal_the_material_struct_defaults) {
  const json& s = schema_document("material");
  const Material m;
  EXPECT_EQ(s.at(json::json_pointer("/properties/thermal/properties/heat_fraction/default")),
            m.thermal.heat_fraction);
  EXPECT_EQ(s.at(json::json_pointer("/properties/damage/properties/D_max/default")),
            m.damage.D_max);
  EXPECT_EQ(s.at(json::json_pointer("/properties/damage/properties/initial_random_max/default")),
            m.damage.initial_random_max);
}

TEST(material_schema, negative_yield_stress_gives_pointer_bound_and_unit) {
  EXPECT_EQ(check(with(library("al-thesis"), "/strength/A", -1.0)),
            (Violations{{"/strength/A", "must be >= 0 (Pa)"}}));
}

TEST(material_schema, poisson_ratio_of_one_half_is_rejected_with_exclusive_bound) {
  EXPECT_EQ(check(with(library("cu-thesis"), "/elastic/nu", 0.5)),
            (Violations{{"/elastic/nu", "must be < 0.5 (-)"}}));
  EXPECT_EQ(check(with(library("cu-thesis"), "/density", 0)),
            (Violations{{"/density", "must be > 0 (kg/m^3)"}}));
  EXPECT_EQ(check(with(library("cu-thesis"), "/thermal/heat_fraction", 1.5)),
            (Violations{{"/thermal/heat_fraction", "must be <= 1 (-)"}}));
}

TEST(material_schema, wrong_type_names_expected_and_actual_type) {
  EXPECT_EQ(check(with(library("al-thesis"), "/density", "2710")),
            (Violations{{"/density", "must be a number, got string"}}));
  EXPECT_EQ(check(with(library("al-thesis"), "/elastic", json::array())),
            (Violations{{"/elastic", "must be an object, got array"}}));
  EXPECT_EQ(check(json::array()), (Violations{{"", "must be an object, got array"}}));
}

TEST(material_schema, missing_required_field_is_reported_at_its_own_pointer) {
  EXPECT_EQ(check(without(library("al-thesis"), "/strength/B")),
            (Violations{{"/strength/B", "required field is missing"}}));
  EXPECT_EQ(check(without(library("al-thesis"), "/source")),
            (Violations{{"/source", "required field is missing"}}));
  EXPECT_EQ(check(without(library("al-thesis"), "/damage/initiation/k_s")),
            (Violations{{"/damage/initiation/k_s", "required field is missing"}}));
}

TEST(material_schema, unknown_fields_are_each_named) {
  json doc = with(library("al-thesis"), "/strength/foo", 1.0);
  doc["strength"]["bar"] = 2.0;  // valijson itself names only the first one
  EXPECT_EQ(check(doc),
            (Violations{{"/strength/bar", "unknown field"}, {"/strength/foo", "unknown field"}}));
  EXPECT_EQ(check(with(library("al-thesis"), "/colour", "grey")),
            (Violations{{"/colour", "unknown field"}}));
}

TEST(material_schema, bad_model_name_lists_the_allowed_values) {
  EXPECT_EQ(check(with(library("cu-thesis"), "/damage/initiation/model", "brittle")),
            (Violations{{"/damage/initiation/model",
                         R"(must be one of "none", "johnson-cook", "shear")"}}));
  EXPECT_EQ(check(with(library("cu-thesis"), "/eos/model", "ideal-gas")),
            (Violations{{"/eos/model", R"(must be one of "linear", "mie-gruneisen")"}}));
  EXPECT_EQ(
      check(with(library("cu-thesis"), "/strength/model", "mechanical-threshold-stress")),
      (Violations{{"/strength/model", R"(must be one of "johnson-cook", "zerilli-armstrong", )"
                                      R"("preston-tonks-wallace", "steinberg-guinan")"}}));
}

TEST(material_schema, fields_of_another_strength_law_are_unknown) {
  EXPECT_EQ(check(with(library("cu-thesis"), "/strength/model", "zerilli-armstrong")),
            (Violations{{"/strength/A", "unknown field"},
                        {"/strength/B", "unknown field"},
                        {"/strength/C", "unknown field"},
                        {"/strength/m", "unknown field"},
                        {"/strength/n", "unknown field"},
                        {"/strength/C0", "required field is missing"},
                        {"/strength/C2", "required field is missing"},
                        {"/strength/C3", "required field is missing"},
                        {"/strength/C4", "required field is missing"}}));
}

TEST(material_schema, fields_of_another_damage_model_are_unknown) {
  // A Johnson-Cook parameter in a shear criterion: only that field is named.
  EXPECT_EQ(check(with(library("al-thesis"), "/damage/initiation/D1", 0.3)),
            (Violations{{"/damage/initiation/D1", "unknown field"}}));
  // Switching the model to johnson-cook without its parameters.
  json doc = with(library("al-thesis"), "/damage/initiation", {{"model", "johnson-cook"}});
  const Violations v = check(doc);
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], (SchemaViolation{"/damage/initiation/D1", "required field is missing"}));
  EXPECT_EQ(v[4], (SchemaViolation{"/damage/initiation/D5", "required field is missing"}));
}

TEST(material_schema, mie_gruneisen_model_needs_its_block) {
  json doc = with(library("steel-hopkinson"), "/eos", {{"model", "mie-gruneisen"}});
  EXPECT_EQ(check(doc), (Violations{{"/eos/mie_gruneisen", "required field is missing"}}));
  // The same model with its block is fine.
  EXPECT_EQ(check(with(library("steel-hopkinson"), "/eos/model", "mie-gruneisen")), Violations{});
}

TEST(material_schema, cubic_coefficients_need_exactly_four_numbers) {
  EXPECT_EQ(check(with(library("al-thesis"), "/damage/initiation/low", {1.0, 2.0, 3.0})),
            (Violations{{"/damage/initiation/low", "must have exactly 4 items, got 3"}}));
  EXPECT_EQ(check(with(library("al-thesis"), "/damage/initiation/high/2", "x")),
            (Violations{{"/damage/initiation/high/2", "must be a number, got string"}}));
}

TEST(material_schema, jc_failure_d3_in_the_abaqus_sign_is_rejected) {
  EXPECT_EQ(check(with(library("cu-thesis"), "/damage/initiation/D3", 3.03)),
            (Violations{{"/damage/initiation/D3", "must be <= 0 (-)"}}));
}

TEST(material_schema, several_faults_are_all_reported_once) {
  json doc = library("ti6al4v-thesis");
  doc["strength"]["A"] = -5.0;
  doc["elastic"]["nu"] = "0.3";
  doc["damage"]["D_max"] = 1.0;
  doc.erase("density");
  const Violations v = check(doc);
  EXPECT_EQ(v.size(), 4u);
  for (const SchemaViolation& expected :
       {SchemaViolation{"/strength/A", "must be >= 0 (Pa)"},
        SchemaViolation{"/elastic/nu", "must be a number, got string"},
        SchemaViolation{"/damage/D_max", "must be < 1 (-)"},
        SchemaViolation{"/density", "required field is missing"}}) {
    EXPECT_EQ(std::count(v.begin(), v.end(), expected), 1) << to_string(expected);
  }
}

TEST(material_schema, input_error_lists_one_violation_per_line) {
  try {
    validate_or_throw("material",
                      with(without(library("al-deck"), "/strength/B"), "/density", -1.0));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.violations().size(), 2u);
    EXPECT_EQ(std::string(e.what()),
              "/density: must be > 0 (kg/m^3)\n/strength/B: required field is missing");
  }
  EXPECT_NO_THROW(validate_or_throw("material", library("al-deck")));
}

TEST(material_schema, unknown_schema_name_is_an_invalid_argument) {
  EXPECT_THROW(schema_document("no-such-schema"), std::invalid_argument);
  EXPECT_THROW(validate("no-such-schema", json::object()), std::invalid_argument);
  try {
    schema_document("no-such-schema");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("material"), std::string::npos) << e.what();
  }
  const std::vector<std::string> names = schema_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "material"), names.end());
}

TEST(material_schema, every_embedded_schema_compiles_and_rejects_a_non_object) {
  for (const std::string& name : schema_names()) {
    EXPECT_TRUE(schema_document(name).is_object()) << name;
    EXPECT_NO_THROW(validate(name, json::object())) << name;
  }
}

TEST(material_schema, validation_is_safe_from_several_threads) {
  const json good = library("cu-thesis");
  const json bad = with(good, "/strength/A", -1.0);
  std::vector<int> failures(4, 0);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < failures.size(); ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 20; ++i) {
        if (!validate("material", good).empty()) ++failures[t];
        if (validate("material", bad) != Violations{{"/strength/A", "must be >= 0 (Pa)"}}) {
          ++failures[t];
        }
      }
    });
  }
  for (std::thread& th : threads) th.join();
  for (int f : failures) EXPECT_EQ(f, 0);
}

// -- generic machinery on inline schemas ------------------------------------

const json shape_schema = json::parse(R"({
  "$schema": "http://json-schema.org/draft-07/schema#",
  "type": "object",
  "additionalProperties": false,
  "required": ["shapes"],
  "properties": {
    "shapes": {"type": "array", "minItems": 1, "items": {"$ref": "#/definitions/shape"}}
  },
  "definitions": {
    "length": {"type": "number", "exclusiveMinimum": 0, "unit": "m", "description": "a length"},
    "shape": {
      "oneOf": [
        {"type": "object", "additionalProperties": false, "required": ["kind", "radius"],
         "properties": {"kind": {"const": "sphere"}, "radius": {"$ref": "#/definitions/length"}}},
        {"type": "object", "additionalProperties": false, "required": ["kind", "size"],
         "properties": {"kind": {"const": "box"},
                        "size": {"type": "array", "minItems": 3, "maxItems": 3,
                                 "items": {"$ref": "#/definitions/length"}}}}
      ]
    }
  }
})");

TEST(schema_translation, one_of_reports_only_the_branch_the_model_names) {
  const json doc = json::parse(R"({"shapes": [
      {"kind": "sphere", "radius": -1},
      {"kind": "box", "size": [1, 0, 2]},
      {"kind": "box", "radius": 1, "size": [1, 1, 1]}]})");
  EXPECT_EQ(validate_against(shape_schema, doc),
            (Violations{{"/shapes/0/radius", "must be > 0 (m)"},
                        {"/shapes/1/size/1", "must be > 0 (m)"},
                        {"/shapes/2/radius", "unknown field"}}));
}

TEST(schema_translation, one_of_without_a_matching_model_names_the_discriminator) {
  EXPECT_EQ(validate_against(shape_schema, json::parse(R"({"shapes": [{"kind": "cone"}]})")),
            (Violations{{"/shapes/0/kind", R"(must be one of "sphere", "box")"}}));
  EXPECT_EQ(validate_against(shape_schema, json::parse(R"({"shapes": [{"radius": 1}]})")),
            (Violations{{"/shapes/0/kind", "required field is missing"}}));
  EXPECT_EQ(validate_against(shape_schema, json::parse(R"({"shapes": []})")),
            (Violations{{"/shapes", "must have at least 1 items, got 0"}}));
  EXPECT_EQ(validate_against(shape_schema, json::parse(R"({"shapes": [{}], "x": 1})")),
            (Violations{{"/shapes/0/kind", "required field is missing"}, {"/x", "unknown field"}}));
}

TEST(schema_translation, pointer_tokens_are_escaped) {
  const json schema = json::parse(R"({"type": "object", "additionalProperties": false})");
  EXPECT_EQ(validate_against(schema, json::parse(R"({"a/b~c": 1})")),
            (Violations{{"/a~1b~0c", "unknown field"}}));
}

TEST(schema_translation, invalid_schema_is_an_invalid_argument) {
  EXPECT_THROW(validate_against(json::parse(R"({"type": 3})"), json::object()),
               std::invalid_argument);
}

// -- parsing ------------------------------------------------------------------

TEST(json_parsing, malformed_text_names_line_and_column) {
  try {
    parse_json_text("{\n  \"density\": 2710,\n  \"elastic\": {\"E\": 70e9,}\n}", "test text");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.violations().size(), 1u);
    EXPECT_EQ(e.violations()[0].pointer, "");
    const std::string& msg = e.violations()[0].message;
    EXPECT_EQ(msg.rfind("malformed JSON in test text at line 3, column 25: ", 0), 0u) << msg;
  }
}

// Named at the field that holds it, in an object or an array, without
// nlohmann's "[json.exception.out_of_range.406]".
TEST(json_parsing, number_beyond_double_range_names_its_field) {
  const auto refusal = [](const std::string& text) {
    try {
      parse_json_text(text, "test text");
    } catch (const InputError& e) {
      return e.violations();
    }
    return Violations{};
  };
  const std::string rule =
      " in test text is beyond the range of a double (magnitude at most 1.8e308)";
  EXPECT_EQ(refusal(R"({"density": 1e400})"),
            (Violations{{"/density", "the number 1e400" + rule}}));
  EXPECT_EQ(refusal(R"({"a": {"v": [1, 2, -1e999]}})"),
            (Violations{{"/a/v/2", "the number -1e999" + rule}}));
  EXPECT_EQ(refusal(R"([1e400])"), (Violations{{"/0", "the number 1e400" + rule}}));
  EXPECT_EQ(refusal(R"(1e400)"), (Violations{{"", "the number 1e400" + rule}}));
}

TEST(json_parsing, field_given_twice_is_rejected_with_its_pointer) {
  try {
    parse_json_text(R"({"strength": {"A": 1, "B": 2, "A": 3}, "x": [0, {"k": 1, "k": 2}]})",
                    "text");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.violations(),
              (Violations{{"/strength/A", "duplicate field (given twice in the same object)"}}));
  }
  try {
    parse_json_text(R"({"x": [0, [1], {"k": 1, "k": 2}]})", "text");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.violations().at(0).pointer, "/x/2/k");
  }
  EXPECT_EQ(parse_json_text(R"({"a": [1, {"b": 2}], "c": {"b": 3}})", "text")["c"]["b"], 3);
}

TEST(json_parsing, missing_and_malformed_files_name_the_file) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "splat_schema_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path missing = dir / "missing.json";
  try {
    read_json_file(missing);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read '" + missing.string() + "': no such file");
  }
  const std::filesystem::path bad = dir / "bad.json";
  std::ofstream(bad) << "{\"a\": 1\n\"b\": 2}";
  try {
    read_json_file(bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("malformed JSON in file '" + bad.string() + "' at line 2, column 3: ", 0),
              0u)
        << msg;
  }
  EXPECT_THROW(read_json_file(dir), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace splat
