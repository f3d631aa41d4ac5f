// contact_pushout: a node found already behind a master segment at the start
// of a step (a fold, or a node exposed by erosion) is moved out through its
// position only (split impulse). Exact expectations for one slave node of
// mass m at rest, depth d below a fixed segment of length L with d < 0.02 L:
// after one Lagrange step it sits on the segment (gap 0), its velocity is
// still zero (a velocity push-out would give it d / dt, 1000 m/s here) and the
// contact has done no work. Deeper than 0.02 L it moves out by 0.02 L per step.
// contact_landing: a node that reaches the segment within the step (a new
// contact, a node-level plastic impact) books the kinetic energy it loses as
// contact work, exactly.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "solver/contact/contact_interface.hpp"

namespace splat {
namespace {

struct OneNode {
  NodeSet nodes;
  std::vector<std::uint8_t> mask;
  ContactInterface contact;
};

// Master segment from (2L, 0) to (L, 0) (outward normal +z), fixed; slave
// node 2 at (1.5 L, -depth) at rest, node 3 far above closes its segment.
OneNode make(double L, double depth) {
  NodeSet n;
  n.x0 = {Vec3(2 * L, 0, 0), Vec3(L, 0, 0), Vec3(1.5 * L, -depth, 0), Vec3(1.5 * L, 10 * L, 0)};
  n.x = n.x0;
  n.v.assign(4, Vec3::Zero());
  n.f.assign(4, Vec3::Zero());
  n.mass.assign(4, 1e-12);
  n.boundary.assign(4, 0);
  std::vector<std::uint8_t> mask{0x3, 0x3, 0, 0};
  ContactSurface master = make_contact_surface(DetectionKind::node_on_segment, {{0, 1, -1, -1}});
  ContactSurface slave = make_contact_surface(DetectionKind::node_on_segment, {{3, 2, -1, -1}});
  ContactSettings s;
  return {n, mask, ContactInterface("m", "s", master, slave, s, true, 4)};
}

TEST(contact_pushout, shallow_penetration_is_removed_through_positions_only) {
  const double L = 1e-5, depth = 1e-8, dt = 1e-11;
  OneNode t = make(L, depth);
  t.contact.lagrange_step(t.nodes, t.mask, dt, std::vector<FeBody>{});
  ASSERT_GT(t.contact.stats().pairs, 0);
  EXPECT_NEAR(t.nodes.x[2].y(), 0.0, 1e-6 * depth);
  EXPECT_EQ(t.nodes.v[2], Vec3::Zero());
  EXPECT_EQ(t.contact.stats().work, 0.0);
  EXPECT_NEAR(t.contact.stats().max_position_correction, depth, 1e-6 * depth);
}

TEST(contact_pushout, deep_penetration_moves_out_two_percent_of_the_face_per_step) {
  const double L = 1e-5, depth = 0.1 * L, dt = 1e-11;
  OneNode t = make(L, depth);
  t.contact.lagrange_step(t.nodes, t.mask, dt, std::vector<FeBody>{});
  ASSERT_GT(t.contact.stats().pairs, 0);
  EXPECT_NEAR(t.nodes.x[2].y(), -depth + 0.02 * L, 1e-6 * depth);
  EXPECT_EQ(t.nodes.v[2], Vec3::Zero());
  EXPECT_LE(t.contact.stats().work, 0.0);
}

// The node approaches at u from a height h = u dt / 4 above the segment: the
// caller has already moved it to its predicted position h - u dt (behind the
// segment). The impulse lands it exactly on the segment at the end of the
// step, so it leaves with v = -h / dt = -u / 4 and has lost
// m (u^2 - u^2 / 16) / 2 of kinetic energy, which the contact work must
// equal (booking p C v_after alone gives -m u^2 (3/16), 40 % of it).
TEST(contact_landing, a_node_landing_within_the_step_books_the_kinetic_energy_it_loses) {
  const double L = 1e-5, dt = 1e-11, u = 500.0, h = 0.25 * u * dt;
  OneNode t = make(L, 0.0);
  t.nodes.x[2] = Vec3(1.5 * L, h - u * dt, 0);
  t.nodes.v[2] = Vec3(0, -u, 0);
  const double m = t.nodes.mass[2];
  t.contact.lagrange_step(t.nodes, t.mask, dt, std::vector<FeBody>{});
  ASSERT_GT(t.contact.stats().pairs, 0);
  EXPECT_NEAR(t.nodes.v[2].y(), -0.25 * u, 1e-9 * u);
  EXPECT_NEAR(t.nodes.x[2].y(), 0.0, 1e-9 * h);
  // Masses are per radian on this axisymmetric interface; its work is of the
  // whole ring (2 pi rad).
  const double lost = std::numbers::pi * m * (u * u - t.nodes.v[2].squaredNorm());
  EXPECT_NEAR(t.contact.stats().work, -lost, 1e-9 * lost);
}

}  // namespace
}  // namespace splat
