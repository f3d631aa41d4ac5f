// SPH detection kinds of the contact interface (contact_search.hpp):
//  - pinball SPH-SPH and SPH particles on FE quads: the bucket search finds
//    exactly the pairs of the all-pairs search on jittered particle clouds;
//  - the pinball geometry: gap |x_s - x_m| - R_s - R_m along the centre line,
//    with radii that follow each particle's deformation; the caps of surface
//    particles: flatter bumps, normal the gap's gradient;
//  - adhesive areas of thesis 2.2.4 on the links: pi R^2 with the mean radius
//    for SPH-SPH, min(face area, pi R^2) for SPH on an FE face.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "solver/contact/contact_interface.hpp"
#include "solver/contact/contact_search.hpp"
#include "solver/mesh/generators.hpp"
#include "solver/mesh/mesh.hpp"
#include "solver/sph/sph_particles.hpp"

namespace splat {
namespace {

struct Clouds {
  std::vector<Vec3> x;
  ContactSurface master, slave;
};

// A ball of particles (spacing d, radius d/2 pinballs) pressed by `overlap`
// into a block of particles (master) or of hexahedra (master faces).
Clouds ball_on_block(double overlap, unsigned seed, bool fe_block,
                     double ball_radius_factor = 1.0) {
  const double d = 1e-6;
  Clouds c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1 * d, 0.1 * d);
  std::vector<int> mids;
  std::vector<double> mr;
  if (fe_block) {
    const HexMesh block =
        hex_box(Vec3(-6 * d, -6 * d, -4 * d), Vec3(6 * d, 6 * d, 0), 9, 9, 3, Grading{});
    for (const Vec3& p : block.nodes) c.x.push_back(p + Vec3(0, 0, jitter(rng)));
    c.master = make_contact_surface(DetectionKind::node_on_quad, block.boundary_faces);
  } else {
    ParticleSpec b;
    b.shape = ParticleShape::box;
    b.lo = Vec3(-6 * d, -6 * d, -4 * d);
    b.hi = Vec3(6 * d, 6 * d, 0);
    b.lattice = Lattice::cubic;
    b.spacing = d;
    const ParticleCloud block = generate_particles(b);
    for (std::size_t i = 0; i < block.size(); ++i) {
      mids.push_back(static_cast<int>(c.x.size()));
      mr.push_back(0.5 * d);
      c.x.push_back(block.x[i] + Vec3(jitter(rng), jitter(rng), jitter(rng)));
    }
    c.master = make_particle_surface(mids, mr);
  }
  ParticleSpec s;
  s.shape = ParticleShape::sphere;
  s.radius = 4 * d;
  s.centre = Vec3(0.3 * d, -0.2 * d, 4 * d - overlap);
  s.spacing = d;
  const ParticleCloud ball = generate_particles(s);
  std::vector<int> sids;
  std::vector<double> sr;
  for (std::size_t i = 0; i < ball.size(); ++i) {
    sids.push_back(static_cast<int>(c.x.size()));
    sr.push_back(0.5 * d * ball_radius_factor);
    c.x.push_back(ball.x[i] + Vec3(jitter(rng), jitter(rng), jitter(rng)));
  }
  c.slave = make_particle_surface(sids, sr);
  return c;
}

void expect_same_pairs(const Clouds& c, std::size_t at_least) {
  const SearchSettings st;
  const auto fast = find_pairs_buckets(c.master, c.slave, c.x, st);
  const auto slow = find_pairs_all_pairs(c.master, c.slave, c.x, st);
  ASSERT_EQ(fast.size(), slow.size());
  EXPECT_GE(fast.size(), at_least);
  for (std::size_t i = 0; i < fast.size(); ++i) {
    EXPECT_EQ(fast[i].slave, slow[i].slave) << i;
    EXPECT_EQ(fast[i].face, slow[i].face) << i;
    EXPECT_EQ(fast[i].geometry.gap, slow[i].geometry.gap) << i;
  }
}

TEST(SphContactSearch, pinball_buckets_match_all_pairs) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double overlap : {-0.5e-6, 0.2e-6, 0.6e-6}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " overlap " << overlap);
      expect_same_pairs(ball_on_block(overlap, seed, false), overlap > 0.0 ? 3 : 0);
      // Unequal radii on the two sides.
      expect_same_pairs(ball_on_block(overlap, seed, false, 1.5), overlap > 0.0 ? 3 : 0);
    }
  }
}

// The same with the block's top layer as caps (normal +z).
TEST(SphContactSearch, cap_buckets_match_all_pairs) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double overlap : {-0.5e-6, 0.2e-6, 0.6e-6}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " overlap " << overlap);
      Clouds c = ball_on_block(overlap, seed, false);
      c.master.cap_normal.assign(c.master.nodes.size(), Vec3::Zero());
      for (std::size_t k = 0; k < c.master.nodes.size(); ++k) {
        if (c.x[c.master.nodes[k]].z() > -0.2e-6) c.master.cap_normal[k] = Vec3::UnitZ();
      }
      expect_same_pairs(c, overlap > 0.0 ? 3 : 0);
    }
  }
}

TEST(SphContactSearch, particles_on_quads_buckets_match_all_pairs) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double overlap : {-0.5e-6, 0.2e-6, 0.6e-6}) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " overlap " << overlap);
      expect_same_pairs(ball_on_block(overlap, seed, true), overlap > 0.0 ? 3 : 0);
    }
  }
}

TEST(SphContactSearch, pinball_gap_is_centre_distance_minus_radii) {
  std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(0.3e-6, 0.4e-6, 1.0e-6)};
  const ContactSurface master = make_particle_surface({0}, {0.6e-6});
  const ContactSurface slave = make_particle_surface({1}, {0.5e-6});
  const auto pairs = find_pairs_all_pairs(master, slave, x, SearchSettings{});
  ASSERT_EQ(pairs.size(), 1u);
  const double dist = x[1].norm();
  EXPECT_NEAR(pairs[0].geometry.gap, dist - 1.1e-6, 1e-18);
  EXPECT_NEAR((pairs[0].geometry.normal - x[1] / dist).norm(), 0.0, 1e-15);
  EXPECT_NEAR(pairs[0].geometry.normal.dot(pairs[0].geometry.tangent1), 0.0, 1e-15);
  EXPECT_NEAR(slave_node_area(slave, 0, x), std::numbers::pi * 0.25e-12, 1e-27);
}

// A point sliding at height z = 2 R over a square layer of master particles
// (spacing 2 R, radius R) in the plane z = 0: over a particle the gap is
// z - R either way; midway between four particles (lateral distance
// sqrt(2) R) the pinballs give sqrt(2 R^2 + z^2) - R = 1.449 R, the caps
// (spheres of radius 4 R centred 3 R below each particle) sqrt(2 R^2 +
// (z + 3 R)^2) - 4 R = 1.196 R: bumps of 0.196 R instead of 0.449 R. The
// cap's normal is the gradient of its gap (what the Lagrange rows assume).
TEST(SphContactSearch, caps_flatten_a_surface_layer_and_their_normal_is_the_gap_gradient) {
  const double R = 0.5e-6, z = 2 * R;
  std::vector<Vec3> x;
  std::vector<int> ids;
  for (int i = -1; i <= 2; ++i) {
    for (int j = -1; j <= 2; ++j) {
      ids.push_back(static_cast<int>(x.size()));
      x.push_back(Vec3(2 * R * i, 2 * R * j, 0));
    }
  }
  ContactSurface master = make_particle_surface(ids, std::vector<double>(ids.size(), R));
  const int slave_id = static_cast<int>(x.size());
  x.push_back(Vec3::Zero());
  const ContactSurface slave = make_particle_surface({slave_id}, {0.0});
  SearchSettings st;
  st.search_margin = 2.0;  // keep every pair in range
  auto smallest = [&](const Vec3& p) {
    x[static_cast<std::size_t>(slave_id)] = p;
    const auto pairs = find_pairs_all_pairs(master, slave, x, st);
    EXPECT_FALSE(pairs.empty());
    return pairs.empty() ? DetectedPair{} : pairs.front();
  };
  const Vec3 top(0, 0, z), middle(R, R, z);
  EXPECT_NEAR(smallest(top).geometry.gap, z - R, 1e-18);
  EXPECT_NEAR(smallest(middle).geometry.gap, std::sqrt(2 * R * R + z * z) - R, 1e-15);
  master.cap_normal.assign(ids.size(), Vec3::UnitZ());
  EXPECT_NEAR(smallest(top).geometry.gap, z - R, 1e-18);
  const double cap_middle = std::sqrt(2 * R * R + (z + 3 * R) * (z + 3 * R)) - 4 * R;
  EXPECT_NEAR(smallest(middle).geometry.gap, cap_middle, 1e-15);
  EXPECT_LT(cap_middle - (z - R), 0.2 * R);
  // The normal is the gradient of the gap of the same pair (central
  // differences of step 1e-4 R).
  const Vec3 p(0.3 * R, -0.7 * R, 1.8 * R);
  const DetectedPair base = smallest(p);
  const double h = 1e-4 * R;
  Vec3 gradient;
  for (int a = 0; a < 3; ++a) {
    const Vec3 e = Vec3::Unit(a) * h;
    x[static_cast<std::size_t>(slave_id)] = p + e;
    double plus = 0.0, minus = 0.0;
    for (const DetectedPair& q : find_pairs_all_pairs(master, slave, x, st)) {
      if (q.face == base.face) plus = q.geometry.gap;
    }
    x[static_cast<std::size_t>(slave_id)] = p - e;
    for (const DetectedPair& q : find_pairs_all_pairs(master, slave, x, st)) {
      if (q.face == base.face) minus = q.geometry.gap;
    }
    gradient[a] = (plus - minus) / (2 * h);
  }
  EXPECT_LT((gradient - base.geometry.normal).norm(), 1e-6);
  EXPECT_GT(base.geometry.normal.z(), 0.9);
}

// A stretched surface layer: two master particles 4 R apart (their layer
// stretched twice along x), a slave particle of radius R in the gap between
// them. As spheres they just touch it (gap 0) and a slave would slip into
// the gap; as the ellipsoids their deformation makes of the initial balls
// (radius 2 R along x), each overlaps it by R. Compression never shrinks a
// pinball below R, and a rotation leaves it round.
TEST(SphContactSearch, deformed_pinballs_follow_the_stretch_of_their_particles) {
  const double R = 0.5e-6;
  std::vector<Vec3> x = {Vec3(0, 0, 0), Vec3(4 * R, 0, 0), Vec3(2 * R, 0, 0)};
  ContactSurface master = make_particle_surface({0, 1}, {R, R});
  const ContactSurface slave = make_particle_surface({2}, {R});
  auto gaps = [&] {
    std::vector<double> g;
    for (const DetectedPair& p : find_pairs_all_pairs(master, slave, x, SearchSettings{})) {
      g.push_back(p.geometry.gap);
    }
    return g;
  };
  auto deform = [&](const Mat3& F, double reach) {
    master.inverse_stretch.assign(2, F.inverse());
    master.reach.assign(2, reach);
  };
  const std::vector<double> round = gaps();
  ASSERT_EQ(round.size(), 2u);
  EXPECT_NEAR(round[0], 0.0, 1e-18);
  deform(Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal(), 2.5 * R);
  for (double g : gaps()) EXPECT_NEAR(g, -R, 1e-18);
  EXPECT_NEAR(master.radius_along(0, Vec3::UnitZ()), R, 1e-18);  // compressed: stays R
  EXPECT_NEAR(master.radius_along(0, Vec3(1, 0, 0.2).normalized()), R * std::sqrt(1.04 / 0.41),
              1e-18);
  deform(Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal(), 1.5 * R);
  EXPECT_NEAR(master.radius_along(0, Vec3::UnitX()), 1.5 * R, 1e-18);  // bounded by reach
  deform(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix(), 1.2 * R);
  for (double g : gaps()) EXPECT_NEAR(g, 0.0, 1e-18);
}

// The shape each particle's deformation gradient gives its pinball: the
// reach is R times the largest principal stretch (so a rigid rotation leaves
// the pinball round), bounded by k_max_pinball_stretch; nearly undeformed,
// inverted and non-finite states keep the sphere.
TEST(SphContactSearch, pinball_shape_follows_the_principal_stretches) {
  const double R = 0.5e-6;
  ContactSurface s = make_particle_surface({0}, {R});
  const Mat3 Q = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  auto shape = [&](const Mat3& F) {
    set_pinball_shape(s, 0, F);
    return s.reach[0];
  };
  EXPECT_NEAR(shape(Q), R, 1e-12 * R);
  for (const Vec3& n : {Vec3(Vec3::UnitX()), Vec3(Vec3(1, -1, 2).normalized())}) {
    EXPECT_NEAR(s.radius_along(0, n), R, 1e-12 * R);
  }
  const Mat3 stretched = Q * Eigen::Vector3d(1.5, 1.0, 0.8).asDiagonal();
  EXPECT_NEAR(shape(stretched), 1.5 * R, 1e-12 * R);
  EXPECT_NEAR(s.radius_along(0, Q * Vec3::UnitX()), 1.5 * R, 1e-12 * R);
  EXPECT_NEAR(s.radius_along(0, Q * Vec3::UnitZ()), R, 1e-12 * R);  // compressed: R
  EXPECT_NEAR(shape(Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal()), k_max_pinball_stretch * R,
              1e-12 * R);
  const Mat3 nearly_identity = Mat3::Identity() + 0.003 * Mat3::Ones();  // norm 0.009
  EXPECT_EQ(shape(nearly_identity), R);
  EXPECT_TRUE(s.inverse_stretch[0].isIdentity(0.0));
  EXPECT_EQ(shape(Eigen::Vector3d(-1.0, 2.0, 1.0).asDiagonal()), R);  // inverted
  Mat3 broken = stretched;
  broken(1, 2) = std::nan("");
  EXPECT_EQ(shape(broken), R);
  EXPECT_TRUE(s.inverse_stretch[0].isIdentity(0.0));
}

// Two particles pressed together (or a particle onto an FE face) bond on
// first touch; the link bonds the smaller side's area. Without their bodies
// (as here) a particle's area is the thesis 2.2.4 pinball area pi R^2; with
// them, its share of its body's surface (SphSurface tests).
TEST(SphContactAdhesion, link_area_is_the_smaller_sides_area) {
  AdhesionParams ap;
  ap.G_c = 1.0;
  ap.activation = ActivationRule::none;
  ContactSettings cs;
  cs.adhesion = ap;
  const double Rs = 0.5e-6, Rm = 0.7e-6;
  auto run = [&](ContactSurface master, ContactSurface slave, NodeSet& n) {
    ContactInterface ci("m", "s", std::move(master), std::move(slave), cs, false, n.size());
    std::vector<std::uint8_t> mask(n.size(), 0);
    const double dt = 1e-9;
    for (int step = 0; step < 4; ++step) {
      for (std::size_t i = 0; i < n.size(); ++i) n.x[i] += dt * n.v[i];  // predict
      ci.lagrange_step(n, mask, dt, {}, {});
    }
    return ci;
  };
  auto nodes_of = [](const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
    NodeSet n;
    n.x0 = n.x = x;
    n.v = v;
    n.f.assign(x.size(), Vec3::Zero());
    n.mass.assign(x.size(), 1e-12);
    n.boundary.assign(x.size(), 0u);
    return n;
  };
  {
    // SPH-SPH: the slave approaches the master particle along z.
    NodeSet n =
        nodes_of({Vec3(0, 0, 0), Vec3(0, 0, Rs + Rm + 5e-9)}, {Vec3::Zero(), Vec3(0, 0, -10.0)});
    const ContactInterface ci =
        run(make_particle_surface({0}, {Rm}), make_particle_surface({1}, {Rs}), n);
    ASSERT_EQ(ci.link_states()[0], LinkState::active);
    EXPECT_NEAR(ci.link_area()[0], std::numbers::pi * Rs * Rs, 1e-24);  // the smaller pinball
  }
  for (double side : {2e-6, 0.5e-6}) {
    // SPH on a square FE face of side `side`: min(face area, pi Rs^2).
    const double h = 0.5 * side;
    NodeSet n =
        nodes_of({Vec3(-h, -h, 0), Vec3(h, -h, 0), Vec3(h, h, 0), Vec3(-h, h, 0),
                  Vec3(0.1 * h, 0, Rs + 5e-9)},
                 {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, -10.0)});
    const ContactInterface ci =
        run(make_contact_surface(DetectionKind::node_on_quad, {{0, 1, 2, 3}}),
            make_particle_surface({4}, {Rs}), n);
    ASSERT_EQ(ci.link_states()[0], LinkState::active);
    // The face's nodes were pushed a little (1e-6 of its area) before the link formed.
    const double expected = std::min(side * side, std::numbers::pi * Rs * Rs);
    EXPECT_NEAR(ci.link_area()[0], expected, 1e-5 * expected) << side;
  }
}

}  // namespace
}  // namespace splat
