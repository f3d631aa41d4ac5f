#include "solver/core/model_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "solver/core/sph_model.hpp"
#include "solver/fe/bulk_viscosity.hpp"
#include "solver/input/schema.hpp"
#include "solver/mesh/generators.hpp"
#include "solver/mesh/mesh.hpp"

namespace splat {

namespace {

[[noreturn]] void fail(const std::string& pointer, const std::string& message) {
  throw InputError({SchemaViolation{pointer, message}});
}

std::string body_pointer(std::size_t b) {
  return "/bodies/" + std::to_string(b);
}

struct Resolution {
  int across = 0;  // elements across the characteristic length
  double h = 0.0;  // element size, m
};

Resolution resolution(const BodySpec& b, double characteristic_length) {
  Resolution r;
  if (b.element_size > 0.0) {
    r.h = b.element_size;
    r.across = std::max(1, static_cast<int>(std::lround(characteristic_length / b.element_size)));
  } else {
    r.across = std::max(1, b.elements_across);
    r.h = characteristic_length / r.across;
  }
  return r;
}

Sector to_sector(SectorKind s) {
  switch (s) {
    case SectorKind::full:
      return Sector::full;
    case SectorKind::half:
      return Sector::half;
    case SectorKind::quarter:
      return Sector::quarter;
  }
  return Sector::full;
}

Grading to_grading(const GradingSpec& g, bool axisymmetric) {
  Grading out;
  out.enabled = g.enabled;
  out.ratio = g.enabled ? g.ratio : 1.0;
  // Scene coordinates are (x, y, z); an axisymmetric focus is (r, z).
  out.focus = axisymmetric ? Vec3(g.focus.x(), g.focus.z(), 0.0) : g.focus;
  out.uniform_extent =
      axisymmetric ? Vec3(g.uniform_extent.x(), g.uniform_extent.z(), 0.0) : g.uniform_extent;
  return out;
}

FeSettings settings_of(const BodySpec& b) {
  FeSettings s;
  s.stiffness_hourglass = b.hourglass == HourglassType::stiffness;
  s.hourglass_coefficient = b.hourglass_coefficient;
  s.q_linear = b.q_linear;
  s.q_quadratic = b.q_quadratic;
  s.erosion = b.erosion;
  s.erosion_min_time_step = b.erosion_min_time_step;
  s.erosion_on_damage = b.erosion_on_damage;
  return s;
}

AxisymMesh axisym_mesh(const BodySpec& b, std::size_t index) {
  const Geometry& g = b.geometry;
  const bool graded = b.grading.enabled;
  const Grading grading = to_grading(b.grading, true);
  switch (g.type) {
    case GeometryType::sphere:
    case GeometryType::half_disc: {
      const Resolution r = resolution(b, g.radius);
      return axisym_half_disc(g.radius, g.centre.z(), r.across);
    }
    case GeometryType::cylinder:
    case GeometryType::rectangle: {
      const double lz = g.z_max - g.z_min;
      const double lc = g.type == GeometryType::cylinder ? g.radius : std::min(g.radius, lz);
      const Resolution r = resolution(b, lc);
      const double ratio = graded ? grading.ratio : 1.0;
      const Vec3& u = grading.uniform_extent;
      return axisym_rectangle(axis_points(0.0, g.radius, r.h, grading.focus.x(), ratio, u.x()),
                              axis_points(g.z_min, g.z_max, r.h, grading.focus.y(), ratio, u.y()));
    }
    case GeometryType::box:
      break;
  }
  fail(body_pointer(index) + "/geometry/type", "a box needs the fe-hex discretization");
}

HexMesh hex_mesh(const BodySpec& b, std::size_t index) {
  const Geometry& g = b.geometry;
  const Grading grading = to_grading(b.grading, false);
  const double ratio = b.grading.enabled ? grading.ratio : 1.0;
  switch (g.type) {
    case GeometryType::sphere: {
      const Resolution r = resolution(b, g.radius);
      return hex_sphere(g.radius, g.centre, r.across, to_sector(b.sector));
    }
    case GeometryType::cylinder: {
      const Resolution r = resolution(b, g.radius);
      const int nz =
          int(axis_points(g.z_min, g.z_max, r.h, grading.focus.z(), ratio, 0.0).size()) - 1;
      return hex_cylinder(g.radius, g.z_min, g.z_max, r.across, nz, to_sector(b.sector), grading);
    }
    case GeometryType::box: {
      const Vec3 size = g.hi - g.lo;
      const Resolution r = resolution(b, size.minCoeff());
      const Vec3& u = grading.uniform_extent;
      return hex_box(axis_points(g.lo.x(), g.hi.x(), r.h, grading.focus.x(), ratio, u.x()),
                     axis_points(g.lo.y(), g.hi.y(), r.h, grading.focus.y(), ratio, u.y()),
                     axis_points(g.lo.z(), g.hi.z(), r.h, grading.focus.z(), ratio, u.z()));
    }
    case GeometryType::half_disc:
    case GeometryType::rectangle:
      break;
  }
  fail(body_pointer(index) + "/geometry/type",
       "half-disc and rectangle need the fe-axisym discretization");
}

// Velocity components a symmetry condition on `bit` fixes.
int symmetry_component(std::uint32_t bit) {
  if (bit & (boundary_x_min | boundary_x_max)) return 0;
  if (bit & (boundary_y_min | boundary_y_max)) return 1;
  if (bit & (boundary_z_min | boundary_z_max)) return 2;
  return -1;
}

// A rigid spin w about the centre of mass of nodes [first, end): v += w x (x - x_c).
void add_spin(NodeSet& nodes, std::size_t first, const Vec3& w) {
  if (w == Vec3::Zero()) return;
  Vec3 moment = Vec3::Zero();
  double mass = 0.0;
  for (std::size_t i = first; i < nodes.size(); ++i) {
    moment += nodes.mass[i] * nodes.x[i];
    mass += nodes.mass[i];
  }
  const Vec3 centre = moment / mass;
  for (std::size_t i = first; i < nodes.size(); ++i) nodes.v[i] += w.cross(nodes.x[i] - centre);
}

// The node set of a named boundary condition, with its mean initial position.
void add_reaction_set(Model& model, const std::string& name, const std::vector<int>& nodes) {
  ReactionSet r;
  r.name = name;
  r.nodes = nodes;
  for (const int i : nodes) r.initial_mean += model.nodes.x[static_cast<std::size_t>(i)];
  if (!nodes.empty()) r.initial_mean /= static_cast<double>(nodes.size());
  model.reaction_sets.push_back(std::move(r));
}

}  // namespace

std::size_t body_node_begin(const Model& model, std::size_t scene_index) {
  const BodyRef r = model.body_refs[scene_index];
  return r.sph ? model.sph_bodies[r.index].node_begin : model.bodies[r.index].node_begin;
}

std::size_t body_node_end(const Model& model, std::size_t scene_index) {
  const BodyRef r = model.body_refs[scene_index];
  return r.sph ? model.sph_bodies[r.index].node_end : model.bodies[r.index].node_end;
}

Vec3 to_user_frame(const Model& model, const Vec3& v) {
  return model.axisymmetric ? Vec3(v.x(), 0.0, v.y()) : v;
}

Vec3 centroid_velocity(const Model& model, const Vec3& momentum, double mass) {
  if (mass <= 0.0) return Vec3::Zero();
  const Vec3 v = momentum / mass;
  return model.axisymmetric ? Vec3(0.0, 0.0, v.y()) : v;
}

ReactionHistory reaction_history(const Model& model, const ReactionSet& set) {
  Vec3 force = Vec3::Zero(), position = Vec3::Zero();
  for (const int i : set.nodes) {
    force -= model.nodes.f[static_cast<std::size_t>(i)];
    position += model.nodes.x[static_cast<std::size_t>(i)];
  }
  ReactionHistory h;
  if (set.nodes.empty()) return h;
  const Vec3 displacement = position / static_cast<double>(set.nodes.size()) - set.initial_mean;
  if (model.axisymmetric) {
    h.force = Vec3(0.0, 0.0, 2.0 * std::numbers::pi * force.y());
    h.displacement = Vec3(displacement.x(), 0.0, displacement.y());
  } else {
    h.force = force;
    h.displacement = displacement;
  }
  return h;
}

Vec3 to_internal_frame(const Model& model, const Vec3& v) {
  return model.axisymmetric ? Vec3(v.x(), v.z(), 0.0) : v;
}

namespace {

// The boundary faces of every body (global node ids; empty for SPH bodies),
// with their boundary tags and nodes per face (2 axisymmetric, 4 hex).
struct BodyFaces {
  std::vector<std::vector<std::array<int, 4>>> faces;
  std::vector<std::vector<std::uint32_t>> tags;
  std::vector<int> counts;
};

// Appends the FE body of scene body `bi` to the model and its faces to `out`.
// make_fe_body takes the velocity in scene coordinates (axisymmetric: the z
// component moves along the axis).
void add_fe_body(const Scene& scene, std::size_t bi, Model& model, BodyFaces& out) {
  const BodySpec& b = scene.bodies[bi];
  model.body_refs.push_back({false, model.bodies.size()});
  const std::size_t first_node = model.nodes.size();
  const int offset = static_cast<int>(first_node);
  BodyMeshInfo info;
  std::vector<std::array<int, 4>> faces;
  std::vector<std::uint32_t> tags;
  if (b.discretization == Discretization::fe_axisym) {
    const AxisymMesh mesh = axisym_mesh(b, bi);
    model.bodies.push_back(make_fe_body(b.name, mesh, b.material, b.switches, settings_of(b),
                                        b.velocity, b.temperature, b.seed, model.nodes));
    for (const auto& q : mesh.quads)
      info.connectivity.insert(info.connectivity.end(), q.begin(), q.end());
    for (std::size_t k = 0; k < mesh.boundary_segments.size(); ++k) {
      const auto& sgm = mesh.boundary_segments[k];
      faces.push_back({offset + sgm[0], offset + sgm[1], 0, 0});
      tags.push_back(mesh.segment_boundary[k]);
    }
    out.counts.push_back(2);
  } else {
    const HexMesh mesh = hex_mesh(b, bi);
    model.bodies.push_back(make_fe_body(b.name, mesh, b.material, b.switches, settings_of(b),
                                        b.velocity, b.temperature, b.seed, model.nodes));
    for (const auto& h : mesh.hexes)
      info.connectivity.insert(info.connectivity.end(), h.begin(), h.end());
    for (std::size_t k = 0; k < mesh.boundary_faces.size(); ++k) {
      std::array<int, 4> f = mesh.boundary_faces[k];
      for (int& id : f) id += offset;
      faces.push_back(f);
      tags.push_back(mesh.face_boundary[k]);
    }
    out.counts.push_back(4);
    add_spin(model.nodes, first_node, b.angular_velocity);
  }
  model.meshes.push_back(std::move(info));
  out.faces.push_back(std::move(faces));
  out.tags.push_back(std::move(tags));
}

BodyFaces add_bodies(const Scene& scene, Model& model) {
  BodyFaces out;
  for (std::size_t bi = 0; bi < scene.bodies.size(); ++bi) {
    const BodySpec& b = scene.bodies[bi];
    if ((b.discretization == Discretization::fe_axisym) != model.axisymmetric) {
      fail(body_pointer(bi) + "/discretization/type",
           "all bodies of a scene must be axisymmetric, or all 3D");
    }
    if (b.discretization != Discretization::sph) {
      add_fe_body(scene, bi, model, out);
      continue;
    }
    const std::size_t first = model.nodes.size();
    model.body_refs.push_back({true, model.sph_bodies.size()});
    model.sph_bodies.push_back(build_sph_body(scene, bi, model.nodes));
    add_spin(model.nodes, first, b.angular_velocity);
    out.faces.emplace_back();
    out.tags.emplace_back();
    out.counts.push_back(0);
  }
  return out;
}

std::size_t body_index(const Scene& scene, const std::string& name, const std::string& pointer) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].name == name) return b;
  }
  fail(pointer, "no body named '" + name + "'");
}

// Absorbing faces (Lysmer-Kuhlemeyer dashpots rho c_p, rho c_s) on the
// faces of FE body `bi` tagged `on`.
void add_absorbing_faces(Model& model, std::size_t bi, std::uint32_t on, const BodyFaces& bf) {
  const FeBody& body = model.bodies[model.body_refs[bi].index];
  const Material& m = body.material;
  const double rho_cp = m.density * body.constants.wave_speed;
  const double rho_cs = std::sqrt(m.density * body.constants.G);
  for (std::size_t k = 0; k < bf.faces[bi].size(); ++k) {
    if (!(bf.tags[bi][k] & on)) continue;
    AbsorbingFace f;
    f.nodes = bf.faces[bi][k];
    f.count = bf.counts[bi];
    f.rho_cp = rho_cp;
    f.rho_cs = rho_cs;
    model.absorbing.push_back(f);
  }
}

// The velocity components (bit c: internal component c) a fixed, velocity or
// symmetry condition prescribes, and their value.
struct Prescribed {
  std::uint8_t mask = 0;
  Vec3 value = Vec3::Zero();
};

Prescribed prescribed(const Model& model, const BoundarySpec& bc, const std::string& ptr) {
  Prescribed p;
  switch (bc.type) {
    case BoundaryType::fixed:
      p.mask = model.axisymmetric ? 0b011 : 0b111;
      break;
    case BoundaryType::velocity:
      // User components x, y, z; axisymmetric x (radial) -> 0, z -> 1.
      for (int c = 0; c < 3; ++c) {
        if (!bc.components[static_cast<std::size_t>(c)]) continue;
        if (model.axisymmetric && c == 1) continue;
        p.mask |= static_cast<std::uint8_t>(1u << (model.axisymmetric && c == 2 ? 1 : c));
      }
      p.value = to_internal_frame(model, bc.velocity);
      break;
    case BoundaryType::symmetry: {
      const int c = symmetry_component(bc.on);
      if (c < 0) fail(ptr + "/on", "a symmetry condition needs a plane (x_min ... z_max)");
      p.mask = static_cast<std::uint8_t>(1u << c);
      break;
    }
    case BoundaryType::absorbing:
      break;
  }
  return p;
}

void add_constraint(Model& model, const BoundarySpec& bc, const std::string& ptr,
                    std::vector<int> set) {
  const Prescribed p = prescribed(model, bc, ptr);
  for (const int i : set) {
    const auto k = static_cast<std::size_t>(i);
    model.constraint_mask[k] |= p.mask;
    for (int c = 0; c < 3; ++c) {
      if (p.mask & (1u << c)) model.constraint_value[k][c] = p.value[c];
    }
  }
  if (!bc.history) return;
  DrivenSet driven;
  driven.nodes = std::move(set);
  driven.mask = p.mask;
  driven.history = *bc.history;
  for (Vec3& v : driven.history.velocity) v = to_internal_frame(model, v);
  model.driven.push_back(std::move(driven));
}

void add_boundary_conditions(const Scene& scene, Model& model, const BodyFaces& bf) {
  const std::size_t n = model.nodes.size();
  model.constraint_mask.assign(n, 0);
  model.constraint_value.assign(n, Vec3::Zero());
  // The symmetry axis of axisymmetric bodies: no radial motion at r = 0.
  if (model.axisymmetric) {
    for (std::size_t i = 0; i < n; ++i) {
      if (model.nodes.boundary[i] & boundary_x_min) model.constraint_mask[i] |= 1u;
    }
  }
  for (std::size_t ci = 0; ci < scene.boundaries.size(); ++ci) {
    const BoundarySpec& bc = scene.boundaries[ci];
    const std::string ptr = "/boundary_conditions/" + std::to_string(ci);
    const std::size_t bi = body_index(scene, bc.body, ptr + "/body");
    const BodyRef ref = model.body_refs[bi];
    std::vector<int> set;  // the condition's nodes
    for (std::size_t i = body_node_begin(model, bi); i < body_node_end(model, bi); ++i) {
      if (model.nodes.boundary[i] & bc.on) set.push_back(static_cast<int>(i));
    }
    if (!bc.name.empty()) add_reaction_set(model, bc.name, set);
    if (ref.sph && bc.type == BoundaryType::absorbing) {
      model.sph_absorbing.push_back(
          build_sph_absorbing(scene.bodies[bi], model.sph_bodies[ref.index], model.nodes, bc.on));
    } else if (ref.sph && bc.type == BoundaryType::symmetry) {
      // Symmetry planes are mirrored ghosts (sph_symmetry_planes): no constraint.
    } else if (bc.type == BoundaryType::absorbing) {
      add_absorbing_faces(model, bi, bc.on, bf);
    } else {
      add_constraint(model, bc, ptr, std::move(set));
    }
  }
}

// The contact surfaces of the scene's bodies: every boundary face of an FE
// body except those on the symmetry axis (axisymmetric) or on one of its
// symmetry planes; every particle of an SPH body as a pinball of radius half
// the spacing (the thesis's "SPH radius": 1.25 um at 2.5 um spacing, 740
// particles in a 12.5 um ball). Not only the initial boundary layers:
// particles flow, a crater sweeps the substrate's first layers aside and
// bares particles that started deep inside, and the particle's own surface
// layers thin out at the jet.
class SurfaceBuilder {
 public:
  SurfaceBuilder(const Scene& scene, const Model& model, const BodyFaces& bf)
      : model_(model), faces_(bf) {
    excluded_.assign(scene.bodies.size(), model.axisymmetric ? boundary_x_min : 0u);
    for (const BoundarySpec& bc : scene.boundaries) {
      if (bc.type != BoundaryType::symmetry) continue;
      for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        if (scene.bodies[b].name == bc.body) excluded_[b] |= bc.on;
      }
    }
  }

  ContactSurface operator()(std::size_t b) const {
    const BodyRef r = model_.body_refs[b];
    if (r.sph) {
      const SphBody& body = model_.sph_bodies[r.index];
      std::vector<int> ids;
      std::vector<double> radius;
      for (std::size_t i = body.node_begin; i < body.node_end; ++i) {
        ids.push_back(static_cast<int>(i));
        radius.push_back(0.5 * body.spacing);
      }
      return make_particle_surface(ids, radius);
    }
    std::vector<std::array<int, 4>> faces;
    for (std::size_t k = 0; k < faces_.faces[b].size(); ++k) {
      if (!(faces_.tags[b][k] & excluded_[b])) faces.push_back(faces_.faces[b][k]);
    }
    const DetectionKind kind =
        model_.axisymmetric ? DetectionKind::node_on_segment : DetectionKind::node_on_quad;
    return make_contact_surface(kind, std::move(faces));
  }

 private:
  const Model& model_;
  const BodyFaces& faces_;
  std::vector<std::uint32_t> excluded_;
};

double bulk_modulus_of(const Model& model, std::size_t b) {
  const BodyRef r = model.body_refs[b];
  return r.sph ? model.sph_bodies[r.index].constants.K : model.bodies[r.index].constants.K;
}

// 0.1 K / h: a tenth of the stiffness of one element layer of the softer
// body (the usual explicit-code default, safe for the time step).
double default_penalty_stiffness(const Model& model, const ContactSurface& master, std::size_t mb,
                                 std::size_t sb, const std::string& ptr) {
  double h = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < master.faces.size(); ++f) {
    h = std::min(h, face_size(master, static_cast<int>(f), model.nodes.x0));
  }
  const double K = std::min(bulk_modulus_of(model, mb), bulk_modulus_of(model, sb));
  if (!std::isfinite(h) || !(h > 0.0)) fail(ptr + "/master", "the body has no contact faces");
  return 0.1 * K / h;
}

void add_contact(const Scene& scene, std::size_t ci, Model& model, const SurfaceBuilder& surface) {
  const InteractionSpec& it = scene.interactions[ci];
  const std::string ptr = "/interactions/" + std::to_string(ci);
  const std::size_t mb = body_index(scene, it.master, ptr + "/master");
  const std::size_t sb = body_index(scene, it.slave, ptr + "/slave");
  if (mb == sb) fail(ptr + "/slave", "must differ from master");
  const bool master_sph = model.body_refs[mb].sph, slave_sph = model.body_refs[sb].sph;
  if (master_sph && !slave_sph) {
    fail(ptr + "/master",
         "an sph master needs an sph slave; make the sph body the slave of "
         "the FE body (SPH particles on FE faces)");
  }
  if ((master_sph || slave_sph) && it.two_pass) {
    fail(ptr + "/two_pass", "two-pass contact is for FE pairs only");
  }
  ContactSettings cs;
  cs.method = it.method;
  cs.friction = it.friction;
  cs.solver.kind = it.solver;
  cs.two_pass = it.two_pass;
  cs.adhesion = it.adhesion;
  ContactSurface master = surface(mb);
  if (it.method == ContactMethod::penalty) {
    cs.penalty_stiffness = it.penalty_stiffness;
    if (!(cs.penalty_stiffness > 0.0)) {
      cs.penalty_stiffness = default_penalty_stiffness(model, master, mb, sb, ptr);
      cs.penalty_mass_scale = 0.1;
    }
  }
  model.contacts.emplace_back(it.master, it.slave, std::move(master), surface(sb), cs,
                              model.axisymmetric, model.nodes.size());
  model.contacts.back().attach_bodies(model.bodies, model.sph_bodies, master_sph,
                                      model.body_refs[mb].index, slave_sph,
                                      model.body_refs[sb].index);
}

void add_wall(const Scene& scene, std::size_t wi, Model& model) {
  const InteractionSpec& it = scene.interactions[wi];
  const std::string ptr = "/interactions/" + std::to_string(wi);
  RigidWall wall;
  wall.point = to_internal_frame(model, it.point);
  wall.normal = to_internal_frame(model, it.normal);
  if (model.axisymmetric && std::abs(it.normal.x()) + std::abs(it.normal.y()) > 0.0) {
    fail(ptr + "/normal", "an axisymmetric scene needs a wall normal along z");
  }
  wall.normal.normalize();
  std::vector<std::size_t> targets;
  if (it.bodies.empty()) {
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) targets.push_back(b);
  } else {
    for (std::size_t k = 0; k < it.bodies.size(); ++k) {
      targets.push_back(body_index(scene, it.bodies[k], ptr + "/bodies/" + std::to_string(k)));
    }
  }
  for (std::size_t b : targets) {
    for (std::size_t i = body_node_begin(model, b); i < body_node_end(model, b); ++i) {
      wall.nodes.push_back(static_cast<int>(i));
    }
  }
  model.walls.push_back(std::move(wall));
}

}  // namespace

Model build_model(const Scene& scene) {
  Model model;
  if (scene.bodies.empty()) fail("/bodies", "at least one body is required");
  model.axisymmetric = scene.bodies.front().discretization == Discretization::fe_axisym;
  const BodyFaces faces = add_bodies(scene, model);
  add_boundary_conditions(scene, model, faces);
  const SurfaceBuilder surface(scene, model, faces);
  for (std::size_t ci = 0; ci < scene.interactions.size(); ++ci) {
    if (scene.interactions[ci].type == InteractionType::contact)
      add_contact(scene, ci, model, surface);
  }
  for (std::size_t wi = 0; wi < scene.interactions.size(); ++wi) {
    if (scene.interactions[wi].type == InteractionType::rigid_wall) add_wall(scene, wi, model);
  }
  return model;
}

namespace {

// Shortest element edge of body b on the current positions, m.
double shortest_edge(const FeBody& b, const NodeSet& n) {
  static constexpr int hex_edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                           {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  static constexpr int quad_edges[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const bool hex = b.kind == ElementKind::hex8;
  double h = std::numeric_limits<double>::infinity();
  for (const auto& conn : b.conn) {
    const int edges = hex ? 12 : 4;
    for (int k = 0; k < edges; ++k) {
      const int a = hex ? hex_edges[k][0] : quad_edges[k][0];
      const int bb = hex ? hex_edges[k][1] : quad_edges[k][1];
      h = std::min(h, (n.x[conn[a]] - n.x[conn[bb]]).norm());
    }
  }
  return h;
}

}  // namespace

double initial_time_step_bound(const Model& model) {
  double dt = std::numeric_limits<double>::infinity();
  for (const FeBody& b : model.bodies) {
    dt = std::min(dt, shortest_edge(b, model.nodes) / b.constants.wave_speed);
  }
  // SPH: the bound of sph_body.hpp at rest, nearest-neighbour distance (the
  // spacing) over the P-wave speed.
  for (const SphBody& b : model.sph_bodies) dt = std::min(dt, b.spacing / b.constants.wave_speed);
  return dt;
}

double initial_closing_speed(const Model& model) {
  const NodeSet& n = model.nodes;
  std::vector<Vec3> mean;
  for (const FeBody& b : model.bodies) {
    Vec3 p = Vec3::Zero();
    double m = 0.0;
    for (std::size_t i = b.node_begin; i < b.node_end; ++i) {
      p += n.mass[i] * n.v[i];
      m += n.mass[i];
    }
    mean.push_back(m > 0.0 ? Vec3(p / m) : Vec3(Vec3::Zero()));
  }
  double dv = 0.0;
  for (std::size_t a = 0; a < mean.size(); ++a) {
    if (!model.walls.empty()) dv = std::max(dv, mean[a].norm());
    for (std::size_t b = a + 1; b < mean.size(); ++b) dv = std::max(dv, (mean[a] - mean[b]).norm());
  }
  return dv;
}

double closing_speed_time_step_bound(const Model& model, double dv) {
  if (!(dv > 0.0)) return std::numeric_limits<double>::infinity();
  double dt = std::numeric_limits<double>::infinity();
  for (const FeBody& b : model.bodies) {
    double L = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < b.num_elements(); ++e) {
      if (b.active[e] && b.char_length[e] > 0.0) L = std::min(L, b.char_length[e]);
    }
    if (!std::isfinite(L)) L = shortest_edge(b, model.nodes);  // before the first evaluation
    const double c = b.constants.wave_speed;
    dt =
        std::min(dt, stable_time_step(L, c, b.settings.q_linear * c + b.settings.q_quadratic * dv));
  }
  return dt;
}

}  // namespace splat
