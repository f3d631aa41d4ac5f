// Contact surfaces that follow erosion (ContactInterface::follow_erosion),
// axisymmetric and 3D: eroding the substrate element under the impact point
// exposes the faces it shared with its live neighbours, which join the master
// surface, while its faces on the axis or on a symmetry plane stay out (they
// were left out of the surface from the start) and its top face is no longer
// live. Eroding the particle's element at the pole does the same for the
// slave surface. Counts by hand: a quadrilateral at the axis shares 2 of its 4
// segments (bottom, outer side), one on the axis; a hexahedron at the corner
// of the quarter model shares 3 of its 6 faces (bottom and two sides), two on
// the symmetry planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/core/model_builder.hpp"
#include "solver/input/scene_io.hpp"

namespace splat {
namespace {

using nlohmann::json;

Model impact_model(const std::string& fidelity) {
  const json doc = {
      {"name", "erosion"},
      {"particle_impact",
       {{"particle", {{"material", "al-thesis"}, {"radius", 12.5e-6}, {"elements_across", 4}}},
        {"velocity", 600.0},
        {"fidelity", fidelity}}}};
  return build_model(read_scene(doc).scene);
}

// The axial coordinate: z in 3D, the second one (r, z) in axisymmetric models.
double axial(const Vec3& x, bool axisym) {
  return axisym ? x.y() : x.z();
}

// Among the elements of `body` with a node at `point` (initial positions),
// the one with the highest centre (substrate: the top layer) or the lowest
// (particle: the pole).
int element_at(const FeBody& body, const NodeSet& n, const Vec3& point, bool highest) {
  int best = -1;
  double best_z = 0.0;
  const int nodes = body.nodes_per_element();
  const bool axisym = body.kind == ElementKind::quad4_axisym;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    bool at = false;
    double z = 0.0;
    for (int a = 0; a < nodes; ++a) {
      const Vec3& x = n.x0[body.conn[e][a]];
      at = at || (x - point).norm() < 1e-12;
      z += axial(x, axisym) / nodes;
    }
    if (at && (best < 0 || (highest ? z > best_z : z < best_z))) {
      best = static_cast<int>(e);
      best_z = z;
    }
  }
  return best;
}

// Whether every node of the face lies on the plane x = 0 or on y = 0 (3D),
// or on the axis r = 0 (axisymmetric, npf 2).
bool on_a_plane(const std::array<int, 4>& f, int npf, const NodeSet& n) {
  bool x0 = true, y0 = npf == 4;
  for (int k = 0; k < npf; ++k) {
    x0 = x0 && n.x0[f[k]].x() == 0.0;
    y0 = y0 && n.x0[f[k]].y() == 0.0;
  }
  return x0 || y0;
}

struct Counts {
  std::size_t master_added = 0, slave_added = 0;
  bool new_face_on_a_plane = false;
  bool top_face_live = true;
};

Counts erode_at_the_impact_point(const std::string& fidelity) {
  Model m = impact_model(fidelity);
  ContactInterface& c = m.contacts.at(0);
  FeBody& substrate = m.bodies.at(m.body_refs.at(1).index);
  FeBody& particle = m.bodies.at(m.body_refs.at(0).index);
  const int npf = c.master_surface().nodes_per_face();
  const std::size_t master0 = c.master_surface().faces.size();
  const std::size_t slave0 = c.slave_surface().faces.size();
  const bool axisym = m.axisymmetric;
  double top = -1.0, pole = 1.0;
  for (std::size_t i = substrate.node_begin; i < substrate.node_end; ++i)
    top = std::max(top, axial(m.nodes.x0[i], axisym));
  for (std::size_t i = particle.node_begin; i < particle.node_end; ++i)
    pole = std::min(pole, axial(m.nodes.x0[i], axisym));
  auto on_axis = [&](double z) { return axisym ? Vec3(0, z, 0) : Vec3(0, 0, z); };
  const int se = element_at(substrate, m.nodes, on_axis(top), true);
  const int pe = element_at(particle, m.nodes, on_axis(pole), false);
  EXPECT_GE(se, 0);
  EXPECT_GE(pe, 0);
  erode_element(substrate, m.nodes, se);
  erode_element(particle, m.nodes, pe);
  c.follow_erosion(m.bodies);
  Counts out;
  const ContactSurface& ms = c.master_surface();
  out.master_added = ms.faces.size() - master0;
  out.slave_added = c.slave_surface().faces.size() - slave0;
  for (std::size_t f = master0; f < ms.faces.size(); ++f) {
    out.new_face_on_a_plane = out.new_face_on_a_plane || on_a_plane(ms.faces[f], npf, m.nodes);
  }
  for (std::size_t f = 0; f < master0; ++f) {
    bool at_origin = false;
    for (int k = 0; k < npf; ++k) {
      at_origin = at_origin || (m.nodes.x0[ms.faces[f][k]] - on_axis(top)).norm() < 1e-12;
    }
    if (at_origin && !c.master_face_live(f)) out.top_face_live = false;
  }
  return out;
}

TEST(contact_erosion, axisymmetric_surfaces_take_the_exposed_segments) {
  const Counts c = erode_at_the_impact_point("fe-axisym");
  EXPECT_EQ(c.master_added, 2u);
  EXPECT_FALSE(c.new_face_on_a_plane);
  EXPECT_FALSE(c.top_face_live);
  // The particle's pole element: its top and outer segments are exposed, its
  // outer arc segment leaves; one segment lies on the axis.
  EXPECT_EQ(c.slave_added, 1u);
}

TEST(contact_erosion, hexahedral_surfaces_take_the_exposed_faces) {
  const Counts c = erode_at_the_impact_point("fe-3d-quarter");
  EXPECT_EQ(c.master_added, 3u);
  EXPECT_FALSE(c.new_face_on_a_plane);
  EXPECT_FALSE(c.top_face_live);
  EXPECT_EQ(c.slave_added, 2u);
}

}  // namespace
}  // namespace splat
