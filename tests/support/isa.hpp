// Runs a check once per instruction set this CPU supports, with that set's
// lane loops active (solver/common/isa.hpp), so that every compiled copy of
// the lane loops is held to the same bits.
#pragma once

#include <gtest/gtest.h>

#include "solver/common/isa.hpp"

namespace splat::test_support {

template <class F>
void for_each_isa(F&& check) {
  const Isa machine = machine_isa();
  for (Isa isa : {Isa::baseline, Isa::x86_64_v3, Isa::x86_64_v4}) {
    if (static_cast<int>(isa) > static_cast<int>(machine)) break;
    SCOPED_TRACE(isa_name(isa));
    set_active_isa(isa);
    check();
    if (::testing::Test::HasFatalFailure()) break;
  }
  set_active_isa(machine);
}

}  // namespace splat::test_support
