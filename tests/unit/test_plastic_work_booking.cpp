// The plastic work a point books against the work its stresses receive (the
// internal energy e, which contains it): the mechanism behind the physics
// guard's plastic-work-excess check (solver/core/physics_guard.hpp). Under
// monotonic shear the two agree to a term first order in the increment;
// shear increments that reverse every step, each larger than the yield
// strain, book sigma_y dp per step while the stresses receive almost no
// work, so the plastic work exceeds e by far.
#include <gtest/gtest.h>

#include <cstdio>

#include "solver/material/point_update.hpp"
#include "tests/support/materials.hpp"

namespace splat {
namespace {

struct Booked {
  double plastic_work;  // J/m^3 of reference volume
  double internal;      // J/m^3 of reference volume
};

// n steps of simple shear increments gamma (sign flipped every step when
// `reverse`) on copper at room temperature, no heating or damage.
Booked shear(double gamma, int n, bool reverse) {
  const Material m = test_support::jc_copper();
  const MaterialConstants mc = derive_constants(m);
  ModelSwitches sw;
  sw.adiabatic_heating = false;
  sw.damage = false;
  PointState st = initial_point_state(m, sw, 300.0, 0.0);
  const double e0 = st.e;
  const double dt = 1e-10;  // s
  for (int k = 0; k < n; ++k) {
    const double g = reverse && k % 2 == 1 ? -gamma : gamma;
    Mat3 d = Mat3::Zero();
    d(0, 1) = d(1, 0) = 0.5 * g;
    update_point(m, mc, sw, st, d, st.J, dt, 1e-5);
  }
  return {st.plastic_work, st.e - e0};
}

// The radial return books the flow stress at the end of each increment
// times dp, the energy the trapezoid of the stresses at both ends: under
// monotonic flow with hardening the two part by a term first order in the
// increment, small for increments well below the plastic strain reached.
TEST(PlasticWorkBooking, monotonic_flow_books_the_work_of_the_stresses) {
  for (double gamma : {1e-4, 1e-2, 0.05}) {
    const Booked b = shear(gamma, static_cast<int>(1.0 / gamma), false);
    std::printf("monotonic shear, increments %g: plastic work / internal energy %.4f\n", gamma,
                b.plastic_work / b.internal);
    EXPECT_GT(b.plastic_work, 0.0);
    EXPECT_LT(b.plastic_work, (1.0 + gamma) * b.internal) << "gamma " << gamma;
  }
}

// Increments of the same size that reverse every step: the stresses receive
// almost no work, the return books sigma_y dp for each.
TEST(PlasticWorkBooking, reversing_increments_book_plastic_work_the_stresses_never_did) {
  // Copper yields at 90 MPa / 46 GPa shear: a shear strain of about 0.003.
  const Booked b = shear(0.05, 20, true);
  std::printf("reversing shear, increments 0.05: plastic work / internal energy %.4f\n",
              b.plastic_work / b.internal);
  EXPECT_GT(b.plastic_work, 5.0 * b.internal);
}

}  // namespace
}  // namespace splat
