#include "solver/core/run_summary.hpp"

#include <nlohmann/json.hpp>

#include "solver/build_info.hpp"

namespace splat {

const char* to_string(RunOutcome outcome) {
  switch (outcome) {
    case RunOutcome::finished:
      return "finished";
    case RunOutcome::unstable:
      return "unstable";
    case RunOutcome::timed_out:
      return "timed-out";
    case RunOutcome::cancelled:
      return "cancelled";
    case RunOutcome::error:
      return "error";
    case RunOutcome::stick:
      return "stick";
    case RunOutcome::rebound:
      return "rebound";
  }
  return "error";
}

namespace {

nlohmann::json vec(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json path_or_null(const std::string& p) {
  return p.empty() ? nlohmann::json(nullptr) : nlohmann::json(p);
}

nlohmann::json number_or_null(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

nlohmann::json body_json(const BodySummary& b) {
  return {{"name", b.name},
          {"elements", b.elements},
          {"nodes", b.nodes},
          {"mass", b.mass},
          {"centroid_velocity", vec(b.centroid_velocity)},
          {"kinetic_energy", b.kinetic_energy},
          {"eroded_elements", b.eroded_elements},
          {"max_plastic_strain", b.max_plastic_strain},
          {"max_temperature", b.max_temperature},
          {"extent_min", vec(b.extent_min)},
          {"extent_max", vec(b.extent_max)}};
}

nlohmann::json interface_json(const InterfaceSummary& c) {
  nlohmann::json j = {{"master", c.master},
                      {"slave", c.slave},
                      {"method", c.method},
                      {"friction", c.friction},
                      {"work", c.work},
                      {"stored", c.stored},
                      {"dissipated", c.dissipated},
                      {"pairs_in_contact", c.pairs_in_contact},
                      {"max_pairs_in_contact", c.max_pairs_in_contact},
                      {"nodes_ever_in_contact", c.nodes_ever_in_contact},
                      {"max_solver_iterations", c.max_solver_iterations},
                      {"max_solver_residual", c.max_solver_residual},
                      {"unconverged_solves", c.unconverged_solves},
                      {"max_penetration", c.max_penetration}};
  if (c.adhesion) {
    j["adhesion"] = {{"work", c.adhesion_work},
                     {"links_activated", c.links_activated},
                     {"links_exhausted", c.links_exhausted},
                     {"links_eroded", c.links_eroded},
                     {"links_active", c.links_active},
                     {"max_links_active", c.max_links_active},
                     {"bonded_area", c.bonded_area},
                     {"max_bonded_area", c.max_bonded_area}};
  }
  return j;
}

// The two-mass figures, added to the summary document j.
void add_two_mass(const TwoMassSummary& t, nlohmann::json& j) {
  j["separation_velocity"] = number_or_null(t.separation_velocity);
  j["two_mass"] = {{"separation_velocity", number_or_null(t.separation_velocity)},
                   {"release_time", number_or_null(t.release_time)},
                   {"final_velocity_M", t.final_velocity_M},
                   {"final_velocity_m", t.final_velocity_m},
                   {"final_gap", t.final_gap},
                   {"link_state", t.link_state},
                   {"link_work", t.link_work},
                   {"work_budget", t.work_budget},
                   {"max_link_force", t.max_link_force},
                   {"dt", t.dt}};
}

// The particle_impact figures, added to the summary document j.
void add_impact(const ImpactSummary& r, nlohmann::json& j) {
  j["verdict"] = r.verdict;
  j["verdict_settled"] = r.settled;
  j["impact_velocity"] = r.impact_velocity;
  j["rebound_velocity"] = r.rebound_velocity;
  j["coefficient_of_restitution"] = r.coefficient_of_restitution;
  j["bonded_area"] = r.bonded_area;
  j["contact_area"] = r.contact_area;
  j["bonded_fraction"] = r.bonded_fraction;
  j["links"] = {{"contact", r.links_contact},     {"activated", r.links_activated},
                {"exhausted", r.links_exhausted}, {"eroded", r.links_eroded},
                {"active", r.links_active},       {"max_active", r.max_links_active}};
  j["thesis_criteria"] = {{"active_link", r.thesis_active_link},
                          {"one_percent_stuck", r.thesis_one_percent}};
  j["energy"]["initial_kinetic"] = r.initial_kinetic;
  j["energy"]["final_particle_kinetic"] = r.final_particle_kinetic;
  j["energy"]["adhesion_dissipated"] = r.adhesion_dissipated;
  j["max_temperature"] = r.max_temperature;
  j["max_plastic_strain"] = r.max_plastic_strain;
  j["flattening_ratio"] = r.flattening_ratio;
  j["penetration_depth"] = r.penetration_depth;
  j["hold_time"] = r.hold_time;
  j["max_time"] = r.max_time;
  j["end_time_rule"] = r.adaptive ? "adaptive" : "fixed";
  j["model"] = {{"name", name_or_empty(r.model)}, {"why", r.why}};
  j["cohesive_zone"] = {{"length", r.cohesive_zone_length},
                        {"element_size", r.interface_element_size},
                        {"elements", r.cohesive_zone_elements}};
  j["bond_energy"] = r.bond_energy;
  j["separating_kinetic_energy"] = r.separating_kinetic;
  const GuardFigures& g = r.guard;
  j["guard"] = {{"interpenetration_checked", g.interpenetration_checked},
                {"max_interpenetration", g.max_interpenetration},
                {"interpenetration_ratio", g.interpenetration_ratio},
                {"nodes_through", g.nodes_through},
                {"eroded_energy_fraction", g.eroded_energy_fraction},
                {"internal_energy_fraction", g.internal_energy_fraction},
                {"plastic_work_excess", g.plastic_work_excess},
                {"failed", name_or_empty(g.failed)}};
}

}  // namespace

nlohmann::json to_json(const RunSummary& s) {
  nlohmann::json j;
  j["solver_version"] = std::string(version());
  j["git_commit"] = std::string(git_commit());
  j["scene"] = s.scene;
  j["outcome"] = to_string(s.outcome);
  j["reason"] = s.reason;
  j["stop_reason"] = name_or_empty(s.stop_reason);
  j["steps"] = s.steps;
  j["end_time"] = s.end_time;
  j["wall_seconds"] = s.wall_seconds;
  j["threads"] = s.threads.team;
  j["thread_use"] = {{"policy", to_string(s.threads.policy)},
                     {"steps_on_team", s.threads.steps_on_team},
                     {"steps_on_one", s.threads.steps_on_one},
                     {"switches", s.threads.switches}};
  const EnergyBudget& e = s.energy;
  j["energy"] = {
      {"initial_total", e.initial_total}, {"kinetic", e.kinetic},
      {"internal", e.internal},           {"plastic_work", e.plastic_work},
      {"hourglass", e.hourglass},         {"artificial_viscosity", e.artificial_viscosity},
      {"absorbed", e.absorbed},           {"eroded", e.eroded},
      {"wall_work", e.wall_work},         {"external_work", e.external_work},
      {"contact_work", e.contact_work},   {"contact_stored", e.contact_stored},
      {"adhesion", e.adhesion},           {"balance_error", e.balance_error}};
  j["bodies"] = nlohmann::json::array();
  for (const BodySummary& b : s.bodies) j["bodies"].push_back(body_json(b));
  j["interfaces"] = nlohmann::json::array();
  for (const InterfaceSummary& c : s.interfaces) j["interfaces"].push_back(interface_json(c));
  if (s.two_mass) add_two_mass(*s.two_mass, j);
  if (s.impact) add_impact(*s.impact, j);
  j["output"] = {{"hdf5", path_or_null(s.hdf5_path)}, {"xdmf", path_or_null(s.xdmf_path)}};
  return j;
}

}  // namespace splat
