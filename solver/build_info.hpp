// Version and git commit the binary was built from; every stored result
// carries both.
#pragma once

#include <string_view>

namespace splat {

std::string_view version();
std::string_view git_commit();

}  // namespace splat
