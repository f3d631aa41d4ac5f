#include "solver/common/omp_wait.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string_view>

namespace splat {

void restart_with_passive_omp_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

std::string omp_wait_policy_at_start() {
  // The environment block the process was started with, NUL-separated.
  std::ifstream in("/proc/self/environ", std::ios::binary);
  const std::string block((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr std::string_view key = "OMP_WAIT_POLICY=";
  std::size_t start = 0;
  while (start < block.size()) {
    std::size_t end = block.find('\0', start);
    if (end == std::string::npos) end = block.size();
    const std::string_view entry(block.data() + start, end - start);
    if (entry.starts_with(key)) return std::string(entry.substr(key.size()));
    start = end + 1;
  }
  return "";
}

}  // namespace splat
