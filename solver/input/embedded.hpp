// Texts compiled into the binary at build time (cmake/embed.cmake): the JSON
// schemas of schemas/ and the material library of materials/.
#pragma once

#include <span>
#include <string_view>

namespace splat {

struct EmbeddedText {
  std::string_view name;  // file name up to its first dot
  std::string_view text;
};

std::span<const EmbeddedText> embedded_schemas();
std::span<const EmbeddedText> embedded_materials();

}  // namespace splat
