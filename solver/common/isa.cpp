#include "solver/common/isa.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

namespace splat {

namespace {

Isa detect() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4")) return Isa::x86_64_v4;
  if (__builtin_cpu_supports("x86-64-v3")) return Isa::x86_64_v3;
  return Isa::baseline;
}

std::atomic<Isa>& active() {
  static std::atomic<Isa> isa{machine_isa()};
  return isa;
}

}  // namespace

Isa machine_isa() {
  static const Isa isa = detect();
  return isa;
}

Isa active_isa() {
  return active().load(std::memory_order_relaxed);
}

void set_active_isa(Isa isa) {
  if (static_cast<int>(isa) > static_cast<int>(machine_isa())) {
    throw std::invalid_argument(std::string("instruction set ") + isa_name(isa) +
                                " is not supported by this CPU (it supports " +
                                isa_name(machine_isa()) + ")");
  }
  active().store(isa, std::memory_order_relaxed);
}

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::x86_64_v4:
      return "x86-64-v4";
    case Isa::x86_64_v3:
      return "x86-64-v3";
    case Isa::baseline:
      break;
  }
  return "x86-64";
}

}  // namespace splat
