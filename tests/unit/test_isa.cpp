// The choice of instruction set for the lane loops (solver/common/isa.hpp).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "solver/common/isa.hpp"

namespace splat {
namespace {

// Every set up to the machine's can be chosen; a set above it is refused
// with a message naming both (on an AVX-512 machine there is none above).
TEST(isa, sets_up_to_the_machines_are_chosen_and_others_refused) {
  const Isa machine = machine_isa();
  EXPECT_EQ(active_isa(), machine);
  for (Isa isa : {Isa::baseline, Isa::x86_64_v3, Isa::x86_64_v4}) {
    SCOPED_TRACE(isa_name(isa));
    if (static_cast<int>(isa) <= static_cast<int>(machine)) {
      set_active_isa(isa);
      EXPECT_EQ(active_isa(), isa);
    } else {
      try {
        set_active_isa(isa);
        ADD_FAILURE() << "accepted a set this CPU lacks";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(isa_name(isa)), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(isa_name(machine)), std::string::npos) << e.what();
      }
      EXPECT_NE(active_isa(), isa);
    }
  }
  set_active_isa(machine);
  EXPECT_EQ(std::string(isa_name(Isa::baseline)), "x86-64");
  EXPECT_EQ(std::string(isa_name(Isa::x86_64_v4)), "x86-64-v4");
}

}  // namespace
}  // namespace splat
