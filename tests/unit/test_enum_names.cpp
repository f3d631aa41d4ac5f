// The name tables of the enums that leave the program (solver/common/enum_names.hpp):
// every value has one name and reads back from it, unknown names read as
// none, and the names are the ones results, stores and schemas already hold.
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "campaign/spec.hpp"
#include "solver/common/enum_names.hpp"
#include "solver/core/stop_reason.hpp"
#include "solver/input/schema.hpp"
#include "solver/scene/fidelity.hpp"

namespace splat {
namespace {

// Every value 0 .. N - 1 of E has a name that parses back to it.
template <NamedEnum E>
void expect_round_trip() {
  const std::size_t n = names_of(E{}).size();
  for (std::size_t i = 0; i < n; ++i) {
    const E value = static_cast<E>(i);
    const std::string_view name = to_string(value);
    EXPECT_FALSE(name.empty()) << "value " << i;
    EXPECT_EQ(parse<E>(name), value) << name;
  }
}

enum class Tint { red, dark_blue };
constexpr NameTable<Tint, 2> k_tints{{{Tint::red, "red"}, {Tint::dark_blue, "dark-blue"}}};
constexpr const auto& names_of(Tint) {
  return k_tints;
}

TEST(EnumNames, tables_must_list_every_value_in_order_with_distinct_names) {
  static_assert(names_in_order(k_tints));
  static_assert(!names_in_order(NameTable<Tint, 2>{{{Tint::dark_blue, "a"}, {Tint::red, "b"}}}));
  static_assert(!names_in_order(NameTable<Tint, 2>{{{Tint::red, "a"}, {Tint::dark_blue, "a"}}}));
  static_assert(!names_in_order(NameTable<Tint, 2>{{{Tint::red, "a"}, {Tint::dark_blue, ""}}}));
  static_assert(to_string(Tint::dark_blue) == "dark-blue");
  static_assert(parse<Tint>("red") == Tint::red);
  static_assert(!parse<Tint>("dark_blue"));
  EXPECT_EQ(all_names<Tint>(), (std::vector<std::string>{"red", "dark-blue"}));
  EXPECT_EQ(name_or_empty(std::optional<Tint>()), "");
  EXPECT_EQ(name_or_empty(std::optional(Tint::dark_blue)), "dark-blue");
}

TEST(EnumNames, stop_reasons_round_trip) {
  expect_round_trip<StopReason>();
  for (const char* unknown : {"", "End-Time", "end_time", "max-steps", "end-time "}) {
    EXPECT_FALSE(parse<StopReason>(unknown)) << unknown;
  }
}

// The names in run summaries, result files and stored campaign results.
TEST(EnumNames, stop_reason_names_are_the_ones_results_hold) {
  EXPECT_EQ(all_names<StopReason>(), (std::vector<std::string>{"end-time",
                                                               "verdict-settled",
                                                               "max-time",
                                                               "undecided",
                                                               "erosion-limit",
                                                               "interpenetration",
                                                               "negative-eroded-energy",
                                                               "negative-internal-energy",
                                                               "plastic-work-excess",
                                                               "non-finite",
                                                               "time-step-collapse",
                                                               "energy-balance",
                                                               "return-mapping",
                                                               "element-inverted",
                                                               "particle-inverted",
                                                               "cancelled",
                                                               "wall-clock-limit",
                                                               "step-limit",
                                                               "error",
                                                               "separated",
                                                               "settled",
                                                               "budget-exceeds-energy",
                                                               "end-time-predicted"}));
}

TEST(EnumNames, fidelities_round_trip) {
  expect_round_trip<Fidelity>();
  for (const char* unknown : {"", "auto", "fe-3d", "fe_axisym", "sph-3d-*"}) {
    EXPECT_FALSE(parse<Fidelity>(unknown)) << unknown;
  }
}

// The scene schema's fidelity choices are auto and the table's names.
TEST(EnumNames, scene_schema_lists_the_fidelities) {
  const nlohmann::json& choices =
      schema_document("scene")["definitions"]["particle_impact"]["properties"]["fidelity"]["enum"];
  std::vector<std::string> expected = {"auto"};
  for (const std::string& name : all_names<Fidelity>()) expected.push_back(name);
  EXPECT_EQ(choices.get<std::vector<std::string>>(), expected);
}

// Every 3D fidelity has two symmetry planes or none; only fe-axisym is
// axisymmetric; an SPH substrate goes with an SPH particle; each predicate
// agrees with the names (sph-*, sph-3d-*, *-quarter, *3d-full).
TEST(EnumNames, fidelity_predicates_partition_the_models) {
  for (std::size_t i = 0; i < names_of(Fidelity{}).size(); ++i) {
    const auto f = static_cast<Fidelity>(i);
    const bool three_d = f != Fidelity::two_mass && f != Fidelity::fe_axisym;
    EXPECT_EQ(is_quarter(f) || is_full_3d(f), three_d) << to_string(f);
    EXPECT_FALSE(is_quarter(f) && is_full_3d(f)) << to_string(f);
    EXPECT_EQ(is_axisymmetric(f), f == Fidelity::fe_axisym) << to_string(f);
    EXPECT_EQ(is_quarter(f), to_string(f).ends_with("-quarter")) << to_string(f);
    EXPECT_EQ(is_full_3d(f), to_string(f).ends_with("3d-full")) << to_string(f);
    EXPECT_EQ(has_sph_particle(f), to_string(f).starts_with("sph-")) << to_string(f);
    EXPECT_EQ(has_sph_substrate(f), to_string(f).starts_with("sph-3d-")) << to_string(f);
    EXPECT_TRUE(!has_sph_substrate(f) || has_sph_particle(f)) << to_string(f);
  }
}

TEST(EnumNames, executors_round_trip) {
  expect_round_trip<campaign::ExecutorKind>();
  for (const char* unknown : {"", "Slurm", "local "}) {
    EXPECT_FALSE(parse<campaign::ExecutorKind>(unknown)) << unknown;
  }
}

// A campaign file and the API's campaign document offer the table's executors.
TEST(EnumNames, campaign_schemas_list_the_executors) {
  const std::vector<std::string> names = all_names<campaign::ExecutorKind>();
  EXPECT_EQ(names, (std::vector<std::string>{"local", "slurm"}));
  for (const char* schema : {"campaign", "api_campaign"}) {
    const nlohmann::json& choices = schema_document(schema)["properties"]["executor"]["enum"];
    EXPECT_EQ(choices.get<std::vector<std::string>>(), names) << schema;
  }
}

}  // namespace
}  // namespace splat
