// Names of enumerations where they leave the program: JSON documents, result
// files, the campaign store, the API and the command line. Each named enum E
// has one table listing every value once, in declaration order, with its
// name, and a hook that argument-dependent lookup finds in E's namespace:
//
//   enum class Colour { red, dark_blue };
//   inline constexpr NameTable<Colour, 2> k_colour_names{{
//       {Colour::red, "red"},
//       {Colour::dark_blue, "dark-blue"},
//   }};
//   static_assert(names_in_order(k_colour_names));
//   constexpr const auto& names_of(Colour) { return k_colour_names; }
//
// to_string and parse read only that table, so each name is spelled once.
// Inside the program the enum is used; the names are converted at the edges.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace splat {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<E, std::string_view>, N>;

// True when `table` lists the values 0, 1, ..., N - 1 of its enum in order,
// each with a distinct non-empty name: a value left out in the middle fails.
template <class E, std::size_t N>
constexpr bool names_in_order(const NameTable<E, N>& table) {
  for (std::size_t i = 0; i < N; ++i) {
    if (static_cast<std::size_t>(table[i].first) != i || table[i].second.empty()) return false;
    for (std::size_t k = 0; k < i; ++k) {
      if (table[k].second == table[i].second) return false;
    }
  }
  return true;
}

// The name of `value` in `table`, nullopt when the table lacks it.
template <class E, std::size_t N>
constexpr std::optional<std::string_view> name_in(const NameTable<E, N>& table, E value) {
  for (const auto& [v, name] : table) {
    if (v == value) return name;
  }
  return std::nullopt;
}

// The value named `name` in `table`, nullopt for an unknown name.
template <class E, std::size_t N>
constexpr std::optional<E> value_in(const NameTable<E, N>& table, std::string_view name) {
  for (const auto& [value, n] : table) {
    if (n == name) return value;
  }
  return std::nullopt;
}

// An enum with a name table found by names_of (above).
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  names_of(e);
};

template <NamedEnum E>
constexpr std::string_view to_string(E value) {
  return name_in(names_of(value), value).value_or(std::string_view());
}

// The value named `name`, nullopt for an unknown name: parse<Colour>("red").
template <NamedEnum E>
constexpr std::optional<E> parse(std::string_view name) {
  return value_in(names_of(E{}), name);
}

// The name of `value`, "" for none.
template <NamedEnum E>
std::string name_or_empty(const std::optional<E>& value) {
  return value ? std::string(to_string(*value)) : std::string();
}

// Every name, in table order (command-line choices, schema checks).
template <NamedEnum E>
std::vector<std::string> all_names() {
  std::vector<std::string> out;
  for (const auto& entry : names_of(E{})) out.emplace_back(entry.second);
  return out;
}

}  // namespace splat
