// The name tables of the enums that leave the program (solver/common/enum_names.hpp):
// every value has one name and reads back from it, unknown names read as
// none, and the names are the ones already written to results and stores.
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "solver/common/enum_names.hpp"
#include "solver/core/stop_reason.hpp"

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

}  // namespace
}  // namespace splat
