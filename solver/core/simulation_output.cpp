// Result-file side of the time loop: histories every history interval,
// field snapshots at the requested times.
#include <cmath>

#include "solver/build_info.hpp"
#include "solver/core/model_builder.hpp"
#include "solver/core/simulation_impl.hpp"
#include "solver/io/result_file.hpp"
#include "solver/material/elasticity.hpp"

namespace splat {

void Simulation::Impl::open_output() {
  if (options.output_dir.empty()) return;
  std::filesystem::create_directories(options.output_dir);
  h5_path = options.output_dir / (scene.name + ".h5");
  std::vector<BodyTopology> topo;
  const int dim = model.axisymmetric ? 2 : 3;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const FeBody& body = model.bodies[b];
    topo.push_back({body.name, body.kind == ElementKind::hex8 ? CellKind::hex8 : CellKind::quad4,
                    dim, model.meshes[b].connectivity, body.node_end - body.node_begin});
  }
  for (const SphBody& body : model.sph_bodies) {
    topo.push_back({body.name, CellKind::point, dim, {}, body.size()});
  }
  std::vector<std::pair<std::string, std::string>> columns = {{"time", "s"},
                                                              {"dt", "s"},
                                                              {"kinetic", "J"},
                                                              {"internal", "J"},
                                                              {"plastic_work", "J"},
                                                              {"hourglass", "J"},
                                                              {"artificial_viscosity", "J"},
                                                              {"absorbed", "J"},
                                                              {"eroded", "J"},
                                                              {"wall_work", "J"},
                                                              {"external_work", "J"},
                                                              {"contact_work", "J"},
                                                              {"contact_stored", "J"},
                                                              {"adhesion", "J"},
                                                              {"balance_error", "-"}};
  for (const FeBody& body : model.bodies) {
    for (const char* c : {"_vx", "_vy", "_vz"}) columns.emplace_back(body.name + c, "m/s");
    columns.emplace_back(body.name + "_kinetic", "J");
  }
  for (const SphBody& body : model.sph_bodies) {
    for (const char* c : {"_vx", "_vy", "_vz"}) columns.emplace_back(body.name + c, "m/s");
    columns.emplace_back(body.name + "_kinetic", "J");
    columns.emplace_back(body.name + "_reference_updates", "-");
  }
  for (std::size_t c = 0; c < model.contacts.size(); ++c) {
    const std::string prefix = "contact" + std::to_string(c) + "_";
    columns.emplace_back(prefix + "pairs_in_contact", "-");
    columns.emplace_back(prefix + "work", "J");
    columns.emplace_back(prefix + "links_active", "-");
    columns.emplace_back(prefix + "bonded_area", "m^2");
    columns.emplace_back(prefix + "adhesion_work", "J");
  }
  for (const ReactionSet& r : model.reaction_sets) {
    for (const char* c : {"_reaction_x", "_reaction_y", "_reaction_z"})
      columns.emplace_back(r.name + c, "N");
    for (const char* c : {"_displacement_x", "_displacement_y", "_displacement_z"})
      columns.emplace_back(r.name + c, "m");
  }
  file = std::make_unique<ResultFile>(h5_path, std::move(topo), std::move(columns));
  file->set_attribute("solver_version", std::string(version()));
  file->set_attribute("git_commit", std::string(git_commit()));
  file->set_attribute("scene_name", scene.name);
  file->set_attribute("scene", resolved.dump());
  file->set_attribute("frame", model.axisymmetric
                                   ? "axisymmetric: coordinates (r, z); energies over 2 pi"
                                   : "3D: coordinates (x, y, z)");
}

void Simulation::Impl::write_history() {
  if (scene.output.history_interval > 0.0) {
    while (next_history_time <= time) next_history_time += scene.output.history_interval;
  }
  if (!file) return;
  std::vector<double> row = {time,
                             dt_half,
                             energy.kinetic,
                             energy.internal,
                             energy.plastic_work,
                             energy.hourglass,
                             energy.artificial_viscosity,
                             energy.absorbed,
                             energy.eroded,
                             energy.wall_work,
                             energy.external_work,
                             energy.contact_work,
                             energy.contact_stored,
                             energy.adhesion,
                             energy.balance_error};
  const NodeSet& n = model.nodes;
  for (const FeBody& body : model.bodies) {
    Vec3 momentum = Vec3::Zero();
    double mass = 0.0, kinetic = 0.0;
    for (std::size_t i = body.node_begin; i < body.node_end; ++i) {
      mass += n.mass[i];
      momentum += n.mass[i] * n.v[i];
      kinetic += 0.5 * n.mass[i] * n.v[i].squaredNorm();
    }
    const Vec3 vc = centroid_velocity(model, momentum, mass);
    row.insert(row.end(), {vc.x(), vc.y(), vc.z(), kinetic * scale()});
  }
  for (const SphBody& body : model.sph_bodies) {
    Vec3 momentum = Vec3::Zero();
    double mass = 0.0, kinetic = 0.0;
    for (std::size_t i = body.node_begin; i < body.node_end; ++i) {
      mass += n.mass[i];
      momentum += n.mass[i] * n.v[i];
      kinetic += 0.5 * n.mass[i] * n.v[i].squaredNorm();
    }
    const Vec3 vc = centroid_velocity(model, momentum, mass);
    row.insert(row.end(),
               {vc.x(), vc.y(), vc.z(), kinetic, static_cast<double>(body.reference_updates)});
  }
  for (const ContactInterface& c : model.contacts) {
    const ContactStats& st = c.stats();
    row.insert(row.end(), {static_cast<double>(st.in_contact), st.work,
                           static_cast<double>(st.links_active), st.bonded_area, st.adhesion_work});
  }
  for (const ReactionSet& r : model.reaction_sets) {
    const ReactionHistory h = reaction_history(model, r);
    row.insert(row.end(), {h.force.x(), h.force.y(), h.force.z(), h.displacement.x(),
                           h.displacement.y(), h.displacement.z()});
  }
  file->append_history(row);
}

// Writes a snapshot when the time has reached the next requested snapshot
// time, or, with final_state, whenever a requested one is still pending (the
// run stopped early).
void Simulation::Impl::write_snapshot(bool final_state) {
  const std::vector<double>& times = scene.output.snapshot_times;
  if (next_snapshot >= times.size()) return;
  if (final_state) {
    next_snapshot = times.size();
  } else {
    if (time < times[next_snapshot] * (1.0 - 1e-12)) return;
    while (next_snapshot < times.size() && times[next_snapshot] <= time * (1.0 + 1e-12)) {
      ++next_snapshot;
    }
  }
  if (!file) return;
  const int dim = model.axisymmetric ? 2 : 3;
  const NodeSet& n = model.nodes;
  // Storage for every body's arrays must outlive the views.
  struct Arrays {
    std::vector<double> coords, velocity, eps_p, temperature, damage, yield, mises, pressure;
    std::vector<double> stress;      // Cauchy stress s - p I, Tensor6 order
    std::vector<double> link_state;  // per node; empty when no interface has this slave body
    std::vector<int> active;
  };
  const std::size_t num_bodies = model.bodies.size() + model.sph_bodies.size();
  std::vector<Arrays> arrays(num_bodies);
  std::vector<BodySnapshot> snaps;
  // The link state (cohesive_law.hpp LinkState: 0 none, 1 contact, 2 active,
  // 3 exhausted, 4 eroded) of each slave node, on the slave body's nodes;
  // nodes off the interface read 0. With several interfaces on one slave
  // body the later one's states win where they are not none.
  const auto body_range = [&](const std::string& name) -> std::pair<std::size_t, std::size_t> {
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      if (model.bodies[b].name == name) return {b, model.bodies[b].node_begin};
    }
    for (std::size_t k = 0; k < model.sph_bodies.size(); ++k) {
      if (model.sph_bodies[k].name == name) {
        return {model.bodies.size() + k, model.sph_bodies[k].node_begin};
      }
    }
    return {num_bodies, 0};
  };
  for (const ContactInterface& c : model.contacts) {
    const auto [b, node_begin] = body_range(c.slave_body());
    if (b >= num_bodies) continue;
    const std::size_t nodes = b < model.bodies.size()
                                  ? model.bodies[b].node_end - model.bodies[b].node_begin
                                  : model.sph_bodies[b - model.bodies.size()].size();
    std::vector<double>& states = arrays[b].link_state;
    states.resize(nodes, 0.0);
    const std::vector<int>& slave_nodes = c.slave_surface().nodes;
    const std::vector<LinkState>& links = c.link_states();
    for (std::size_t k = 0; k < slave_nodes.size() && k < links.size(); ++k) {
      const std::size_t local = static_cast<std::size_t>(slave_nodes[k]) - node_begin;
      if (links[k] != LinkState::none && local < nodes) {
        states[local] = static_cast<double>(links[k]);
      }
    }
  }
  // Node coordinates and velocity; one cell's fields (element centre or
  // particle); the snapshot of a body from its arrays.
  const auto add_node = [&](Arrays& a, std::size_t i) {
    for (int c = 0; c < dim; ++c) {
      a.coords.push_back(n.x[i][c]);
      a.velocity.push_back(n.v[i][c]);
    }
  };
  const auto add_cell = [](Arrays& a, const PointState& st, int active) {
    a.eps_p.push_back(st.eps_p);
    a.temperature.push_back(st.T);
    a.damage.push_back(st.D);
    a.yield.push_back(st.sigma_y);
    a.mises.push_back(von_mises(st.s));
    a.pressure.push_back(st.p);
    const Mat3& s = st.s;
    a.stress.insert(a.stress.end(),
                    {s(0, 0) - st.p, s(0, 1), s(0, 2), s(1, 1) - st.p, s(1, 2), s(2, 2) - st.p});
    a.active.push_back(active);
  };
  // SPH bodies: one point per particle, every field on the points.
  const auto add_snapshot = [&](const std::string& name, const Arrays& a, bool on_cells) {
    BodySnapshot s;
    s.body = name;
    s.coordinates = a.coords;
    s.fields = {{"velocity", "m/s", false, dim, a.velocity},
                {"plastic_strain", "-", on_cells, 1, a.eps_p},
                {"temperature", "K", on_cells, 1, a.temperature},
                {"damage", "-", on_cells, 1, a.damage},
                {"yield_stress", "Pa", on_cells, 1, a.yield},
                {"von_mises", "Pa", on_cells, 1, a.mises},
                {"pressure", "Pa", on_cells, 1, a.pressure},
                {"stress", "Pa", on_cells, 6, a.stress}};
    if (!a.link_state.empty()) s.fields.push_back({"link_state", "-", false, 1, a.link_state});
    s.active_cells = a.active;
    snaps.push_back(std::move(s));
  };
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const FeBody& body = model.bodies[b];
    Arrays& a = arrays[b];
    for (std::size_t i = body.node_begin; i < body.node_end; ++i) add_node(a, i);
    for (std::size_t e = 0; e < body.num_elements(); ++e) {
      add_cell(a, body.state[e], body.active[e]);
    }
    add_snapshot(body.name, a, true);
  }
  for (std::size_t k = 0; k < model.sph_bodies.size(); ++k) {
    const SphBody& body = model.sph_bodies[k];
    Arrays& a = arrays[model.bodies.size() + k];
    for (std::size_t p = 0; p < body.size(); ++p) {
      add_node(a, body.node_begin + p);
      add_cell(a, body.state[p], body.active[p]);
    }
    add_snapshot(body.name, a, false);
  }
  file->write_snapshot(time, snaps);
  ++snapshots_written;
}

}  // namespace splat
