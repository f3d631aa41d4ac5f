#include "solver/core/impact_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "solver/common/parallel.hpp"
#include "solver/core/physics_guard.hpp"

namespace splat {
namespace {

constexpr double k_hold_transits = 8.0;     // hold time in particle transits R / c_p, -
constexpr double k_wall_touch = 1e-9;       // gap / R below which a node touches a rigid wall, -
constexpr double k_thesis_fraction = 0.01;  // thesis: > 1 % of the most links ever active

std::string format_reason(const char* fmt, double a, double b) {
  char buf[240];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// Scene index of the body named `name` (FE or SPH), -1 if none.
int body_index(const Model& model, const std::string& name) {
  for (std::size_t b = 0; b < model.body_refs.size(); ++b) {
    const BodyRef& r = model.body_refs[b];
    const std::string& n = r.sph ? model.sph_bodies[r.index].name : model.bodies[r.index].name;
    if (n == name) return static_cast<int>(b);
  }
  return -1;
}

// Node (particle) range of scene body b.
struct NodeRange {
  std::size_t begin = 0, end = 0;
};
NodeRange nodes_of(const Model& model, int b) {
  return {body_node_begin(model, static_cast<std::size_t>(b)),
          body_node_end(model, static_cast<std::size_t>(b))};
}

// Height of node position p along the substrate normal (internal frame).
double height(const Model& model, const Vec3& p) {
  return model.axisymmetric ? p.y() : p.z();
}

struct BodyMotion {
  double mass = 0.0;  // kg, per radian in 2D
  Vec3 velocity = Vec3::Zero();
  double kinetic = 0.0;  // J, per radian in 2D
  double height = 0.0;   // m, of the centre of mass along the substrate normal
};

BodyMotion motion(const Model& model, int b) {
  BodyMotion out;
  if (b < 0) return out;
  const NodeRange body = nodes_of(model, b);
  const NodeSet& n = model.nodes;
  // (mass, momentum, kinetic energy, mass x height) over fixed blocks: the same bits for
  // any thread count.
  using Sums = Eigen::Matrix<double, 6, 1>;
  constexpr std::size_t block = 1024, min_parallel = 4096;
  const Sums sums = block_sum(body.end - body.begin, block, min_parallel, Sums(Sums::Zero()),
                              [&](std::size_t lo, std::size_t hi) {
                                Sums sum = Sums::Zero();
                                for (std::size_t k = lo; k < hi; ++k) {
                                  const std::size_t i = body.begin + k;
                                  const double m = n.mass[i];
                                  if (m <= 0.0) continue;
                                  sum(0) += m;
                                  sum.segment<3>(1) += m * n.v[i];
                                  sum(4) += 0.5 * m * n.v[i].squaredNorm();
                                  sum(5) += m * height(model, n.x[i]);
                                }
                                return sum;
                              });
  out.mass = sums(0);
  out.kinetic = sums(4);
  out.height = out.mass > 0.0 ? sums(5) / out.mass : 0.0;
  out.velocity = centroid_velocity(model, Vec3(sums.segment<3>(1)), out.mass);
  return out;
}

double finite_or_zero(double x) {
  return std::isfinite(x) ? x : 0.0;
}

}  // namespace

ImpactRun::ImpactRun(const ImpactSpec& spec, const Model& model, double max_time,
                     double energy_limit)
    : spec_(spec), monitor_(VerdictSettings{}), max_time_(max_time), energy_limit_(energy_limit) {
  particle_ = body_index(model, spec.particle);
  substrate_ = spec.substrate.empty() ? -1 : body_index(model, spec.substrate);
  for (std::size_t c = 0; c < model.contacts.size(); ++c) {
    if (model.contacts[c].slave_body() == spec.particle) contact_ = static_cast<int>(c);
  }
  if (contact_ >= 0) {
    const auto& adhesion = model.contacts[contact_].settings().adhesion;
    links_hold_ = adhesion.has_value() && adhesion->G_c > 0.0;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  if (particle_ >= 0) {
    const BodyRef& ref = model.body_refs[particle_];
    const NodeRange p = nodes_of(model, particle_);
    for (std::size_t i = p.begin; i < p.end; ++i) {
      lo = std::min(lo, height(model, model.nodes.x0[i]));
      hi = std::max(hi, height(model, model.nodes.x0[i]));
    }
    // SPH: particle centres lie half a spacing inside the surface.
    half_spacing_ = ref.sph ? 0.5 * model.sph_bodies[ref.index].spacing : 0.0;
    radius_ = 0.5 * (hi - lo) + half_spacing_;
    const Material& material =
        ref.sph ? model.sph_bodies[ref.index].material : model.bodies[ref.index].material;
    settings_.hold_time = k_hold_transits * radius_ / p_wave_speed(material);
    guard_interval_ = radius_ / p_wave_speed(material);
    settings_.radius = radius_;
  }
  monitor_ = ImpactMonitor(settings_);
}

ImpactSample ImpactRun::sample(double time, const Model& model) const {
  ImpactSample s;
  s.time = time;
  const double scale = model.axisymmetric ? 2.0 * std::numbers::pi : 1.0;
  const BodyMotion p = motion(model, particle_);
  const BodyMotion sub = motion(model, substrate_);
  const Vec3 rel = p.velocity - sub.velocity;
  s.v_normal = rel.z();
  s.v_tangential = std::hypot(rel.x(), rel.y());
  s.kinetic_rel = 0.5 * p.mass * scale * rel.squaredNorm();
  const double leaving = std::max(s.v_normal, 0.0);
  s.kinetic_leaving = 0.5 * p.mass * scale * (leaving * leaving + s.v_tangential * s.v_tangential);
  if (contact_ >= 0) {
    const ContactStats& st = model.contacts[contact_].stats();
    s.links_active = links_hold_ ? st.links_active : 0;
    s.pairs_in_contact = st.in_contact;
    s.bonded_area = links_hold_ ? st.bonded_area : 0.0;
    s.bond_energy = links_hold_ ? st.bond_energy : 0.0;
    s.bond_damage = links_hold_ ? st.bond_damage : 0.0;
    s.bond_force = links_hold_ ? st.bond_force : 0.0;
    if (s.links_active > 0) s.bond_offset = p.height - bonded_height(model);
  } else if (particle_ >= 0) {
    const NodeRange body = nodes_of(model, particle_);
    for (std::size_t i = body.begin; i < body.end; ++i) {
      if (model.nodes.mass[i] > 0.0 &&
          height(model, model.nodes.x[i]) <= half_spacing_ + k_wall_touch * radius_)
        ++s.pairs_in_contact;
    }
  }
  return s;
}

void ImpactRun::cohesive_zone(const Model& model, ImpactSummary& r) const {
  const ContactInterface& c = model.contacts[contact_];
  if (!c.settings().adhesion) return;
  const BodyRef& p = model.body_refs[particle_];
  const Material& mp = p.sph ? model.sph_bodies[p.index].material : model.bodies[p.index].material;
  const Material* ms = &mp;
  if (substrate_ >= 0) {
    const BodyRef& s = model.body_refs[substrate_];
    ms = s.sph ? &model.sph_bodies[s.index].material : &model.bodies[s.index].material;
  }
  // A flow-stress cap: the mean strength of the links active at the end, or
  // the weaker material's initial yield stress when none is.
  AdhesionParams law = *c.settings().adhesion;
  if (law.cap_at_flow_stress) {
    const double initial =
        std::min(initial_yield_stress(mp.strength), initial_yield_stress(ms->strength));
    const double now = c.stats().bond_strength;
    law.sigma_c = link_strength(law, now > 0.0 ? now : initial);
  }
  r.cohesive_zone_length =
      cohesive_zone_length(law, mp.elastic.E, mp.elastic.nu, ms->elastic.E, ms->elastic.nu);
  if (p.sph) {
    r.interface_element_size = model.sph_bodies[p.index].spacing;
  } else {
    // Faces of the particle's surface with a node that touched (all faces
    // when none did), on the initial mesh.
    const ContactSurface& surface = c.slave_surface();
    const std::vector<LinkState>& states = c.link_states();
    double sum = 0.0, sum_all = 0.0;
    long long n = 0;
    for (std::size_t f = 0; f < surface.faces.size(); ++f) {
      const double size = face_size(surface, static_cast<int>(f), model.nodes.x0);
      sum_all += size;
      for (int k = 0; k < surface.nodes_per_face(); ++k) {
        const auto it =
            std::lower_bound(surface.nodes.begin(), surface.nodes.end(), surface.faces[f][k]);
        const std::size_t idx = static_cast<std::size_t>(it - surface.nodes.begin());
        if (idx < states.size() && states[idx] != LinkState::none) {
          sum += size;
          ++n;
          break;
        }
      }
    }
    const double faces = static_cast<double>(surface.faces.size());
    r.interface_element_size =
        n > 0 ? sum / static_cast<double>(n) : (faces > 0 ? sum_all / faces : 0.0);
  }
  r.cohesive_zone_elements =
      r.interface_element_size > 0.0 ? r.cohesive_zone_length / r.interface_element_size : 0.0;
}

double ImpactRun::bonded_height(const Model& model) const {
  const ContactInterface& c = model.contacts[contact_];
  const std::vector<LinkState>& states = c.link_states();
  const std::vector<int>& ids = c.slave_surface().nodes;
  double sum = 0.0;
  long long count = 0;
  for (std::size_t k = 0; k < states.size() && k < ids.size(); ++k) {
    if (states[k] != LinkState::active) continue;
    sum += height(model, model.nodes.x[ids[k]]);
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

namespace {

// Whether scene body `b` (-1: none) has lost an element or particle:
// erosion bares nodes that lay inside the body, and one the other body's
// surface had passed, legitimately, until its element went.
bool eroded(const Model& model, int b) {
  if (b < 0) return false;
  const BodyRef& ref = model.body_refs[static_cast<std::size_t>(b)];
  const std::vector<std::uint8_t>& active =
      ref.sph ? model.sph_bodies[ref.index].active : model.bodies[ref.index].active;
  return std::find(active.begin(), active.end(), std::uint8_t{0}) != active.end();
}

}  // namespace

std::optional<VerdictDecision> ImpactRun::observe(double time, const Model& model) {
  last_ = sample(time, model);
  if (time >= next_guard_time_ && !eroded(model, particle_) && !eroded(model, substrate_)) {
    Interpenetration now =
        measure_interpenetration(model, GuardInput{particle_, substrate_, contact_, energy_limit_});
    now.time = time;
    worst_ = worse(worst_, now);
    next_guard_time_ = time + guard_interval_;
  }
  if (initial_kinetic_ < 0.0) {
    const double scale = model.axisymmetric ? 2.0 * std::numbers::pi : 1.0;
    initial_kinetic_ = motion(model, particle_).kinetic * scale;
  }
  return monitor_.update(last_);
}

void ImpactRun::particle_shape(const Model& model, ImpactSummary& r) const {
  if (particle_ < 0) return;
  const NodeRange body = nodes_of(model, particle_);
  const NodeSet& n = model.nodes;
  // Full 3D models (fe-3d-full, sph-3d-full, sph-on-fe-3d-full): lateral
  // radius about the particle's axis through its centre of mass; quarter
  // and axisymmetric models: about the z axis.
  const bool full_3d = !model.axisymmetric && spec_.model && is_full_3d(*spec_.model);
  double cx = 0.0, cy = 0.0, m = 0.0;
  if (full_3d) {
    for (std::size_t i = body.begin; i < body.end; ++i) {
      cx += n.mass[i] * n.x[i].x();
      cy += n.mass[i] * n.x[i].y();
      m += n.mass[i];
    }
    if (m > 0.0) cx /= m, cy /= m;
  }
  double r_max = 0.0, z_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = body.begin; i < body.end; ++i) {
    if (n.mass[i] <= 0.0) continue;
    const double lateral =
        model.axisymmetric ? n.x[i].x() : std::hypot(n.x[i].x() - cx, n.x[i].y() - cy);
    r_max = std::max(r_max, lateral);
    z_min = std::min(z_min, height(model, n.x[i]));
  }
  r.flattening_ratio = radius_ > 0.0 ? (r_max + half_spacing_) / radius_ : 0.0;
  r.penetration_depth = std::isfinite(z_min) ? std::max(0.0, half_spacing_ - z_min) : 0.0;
}

void ImpactRun::interface_figures(const Model& model, const ImpactSample& now,
                                  ImpactSummary& r) const {
  if (contact_ < 0) {
    r.links_contact = now.pairs_in_contact;
    return;
  }
  const ContactInterface& c = model.contacts[contact_];
  const ContactStats& st = c.stats();
  r.links_contact = st.ever_in_contact;
  r.links_activated = st.links_activated;
  r.links_exhausted = st.links_exhausted;
  r.links_eroded = st.links_eroded;
  r.links_active = st.links_active;
  r.max_links_active = st.max_links_active;
  r.bonded_area = st.bonded_area;
  r.adhesion_dissipated = st.adhesion_work;
  const std::vector<LinkState>& states = c.link_states();
  for (std::size_t k = 0; k < states.size(); ++k) {
    if (states[k] == LinkState::none) continue;
    r.contact_area += slave_node_area(c.slave_surface(), static_cast<int>(k), model.nodes.x);
  }
  r.contact_area *= model.axisymmetric ? 2.0 * std::numbers::pi : 1.0;
  cohesive_zone(model, r);
  r.bonded_fraction = r.contact_area > 0.0 ? std::min(r.bonded_area / r.contact_area, 1.0) : 0.0;
}

double ImpactRun::eroded_fraction(const Model& model) const {
  if (particle_ < 0 || model.body_refs[particle_].sph) return 0.0;  // SPH particles stay
  const FeBody& body = model.bodies[model.body_refs[particle_].index];
  double total = 0.0, gone = 0.0;
  for (std::size_t e = 0; e < body.num_elements(); ++e) {
    total += body.element_mass[e];
    if (!body.active[e]) gone += body.element_mass[e];
  }
  return total > 0.0 ? gone / total : 0.0;
}

namespace {

// Says which term broke the energy balance (all as fractions of the initial
// energy).
void explain_energy_balance(RunSummary& s) {
  const EnergyBudget& e = s.energy;
  const double E0 = std::max(e.initial_total, 1e-300);
  s.reason += format_reason(" (contact work %+.3g, eroded %.3g of the initial energy",
                            e.contact_work / E0, e.eroded / E0);
  s.reason +=
      format_reason("; hourglass %.3g, kinetic now %.3g)", e.hourglass / E0, e.kinetic / E0);
}

// A run that went unstable may have left non-finite numbers behind: the
// figures report zero for those (the outcome says the run is not usable).
void zero_non_finite(ImpactSummary& r) {
  for (double* x : {&r.rebound_velocity,
                    &r.coefficient_of_restitution,
                    &r.bonded_area,
                    &r.contact_area,
                    &r.bonded_fraction,
                    &r.initial_kinetic,
                    &r.final_particle_kinetic,
                    &r.adhesion_dissipated,
                    &r.max_temperature,
                    &r.max_plastic_strain,
                    &r.flattening_ratio,
                    &r.penetration_depth,
                    &r.bond_energy,
                    &r.separating_kinetic,
                    &r.cohesive_zone_length,
                    &r.interface_element_size,
                    &r.cohesive_zone_elements,
                    &r.guard.max_interpenetration,
                    &r.guard.interpenetration_ratio,
                    &r.guard.eroded_energy_fraction,
                    &r.guard.internal_energy_fraction,
                    &r.guard.plastic_work_excess}) {
    *x = finite_or_zero(*x);
  }
}

}  // namespace

bool ImpactRun::verdict_allowed(RunSummary& s, const Model& model, bool own_end,
                                ImpactSummary& r) const {
  std::string guard_reason;
  const std::optional<StopReason> failed =
      check_physics(model, s.energy, GuardInput{particle_, substrate_, contact_, energy_limit_},
                    r.guard, guard_reason, worst_);
  const double eroded = eroded_fraction(model);
  // Above the scene's max_eroded_fraction the remaining body no longer
  // represents the particle: the verdict is withheld (outcome unstable).
  if (own_end && eroded > spec_.max_eroded_fraction) {
    s.outcome = RunOutcome::unstable;
    s.stop_reason = StopReason::erosion_limit;
    s.reason = format_reason(
        "no verdict: %.1f %% of the particle's mass was eroded (limit max_eroded_fraction "
        "%.0f %%): the particle broke up (elements at the damage cap) or its mesh could not "
        "follow the deformation",
        100.0 * eroded, 100.0 * spec_.max_eroded_fraction);
    return false;
  }
  if (own_end && failed) {
    s.outcome = RunOutcome::unstable;
    s.stop_reason = failed;
    s.reason = "no verdict: " + guard_reason;
    return false;
  }
  if (!own_end && s.stop_reason == StopReason::energy_balance) explain_energy_balance(s);
  return own_end;
}

void ImpactRun::apply_decision(RunSummary& s, ImpactSummary& r, const VerdictDecision& decision,
                               bool settled) const {
  if (decision.verdict == ImpactVerdict::undecided) {
    s.outcome = RunOutcome::unstable;
    s.stop_reason = StopReason::undecided;
    s.reason = "no verdict: " + decision.reason;
    return;
  }
  r.verdict = to_string(decision.verdict);
  r.settled = decision.settled;
  s.outcome = decision.verdict == ImpactVerdict::stick ? RunOutcome::stick : RunOutcome::rebound;
  s.reason = decision.reason;
  if (!spec_.adaptive_end) {
    s.stop_reason = StopReason::end_time;
  } else {
    s.stop_reason = settled ? StopReason::verdict_settled : StopReason::max_time;
  }
}

void ImpactRun::finish(RunSummary& s, const Model& model,
                       const std::optional<VerdictDecision>& settled) {
  ImpactSummary r;
  r.model = spec_.model;
  r.why = spec_.why;
  r.adaptive = spec_.adaptive_end;
  r.hold_time = settings_.hold_time;
  r.max_time = max_time_;
  r.impact_velocity = spec_.velocity;
  const double scale = model.axisymmetric ? 2.0 * std::numbers::pi : 1.0;
  const ImpactSample now = sample(s.end_time, model);
  r.rebound_velocity = now.v_normal;
  r.coefficient_of_restitution =
      spec_.velocity > 0.0 ? std::max(now.v_normal, 0.0) / spec_.velocity : 0.0;
  r.initial_kinetic = std::max(initial_kinetic_, 0.0);
  r.final_particle_kinetic = motion(model, particle_).kinetic * scale;
  particle_shape(model, r);
  for (const BodySummary& b : s.bodies) {
    r.max_temperature = std::max(r.max_temperature, b.max_temperature);
    r.max_plastic_strain = std::max(r.max_plastic_strain, b.max_plastic_strain);
  }
  interface_figures(model, now, r);
  r.thesis_active_link = r.links_active > 0;
  r.thesis_one_percent =
      r.max_links_active > 0 && static_cast<double>(r.links_active) >
                                    k_thesis_fraction * static_cast<double>(r.max_links_active);
  r.bond_energy = now.bond_energy;
  r.separating_kinetic = now.kinetic_leaving;
  r.verdict = "none";
  const bool own_end = settled.has_value() || s.stop_reason == StopReason::end_time;
  if (verdict_allowed(s, model, own_end, r)) {
    apply_decision(s, r, settled ? *settled : monitor_.at_end(now), settled.has_value());
  }
  zero_non_finite(r);
  s.impact = r;
}

void write_impact_attributes(ResultFile& file, const RunSummary& s) {
  const ImpactSummary& r = *s.impact;
  file.set_attribute("verdict", r.verdict);
  file.set_attribute("verdict_settled", static_cast<long long>(r.settled));
  file.set_attribute("impact_velocity", r.impact_velocity, "m/s");
  file.set_attribute("rebound_velocity", r.rebound_velocity, "m/s");
  file.set_attribute("coefficient_of_restitution", r.coefficient_of_restitution, "-");
  file.set_attribute("bonded_area", r.bonded_area, "m^2");
  file.set_attribute("contact_area", r.contact_area, "m^2");
  file.set_attribute("bonded_fraction", r.bonded_fraction, "-");
  file.set_attribute("links.contact", r.links_contact);
  file.set_attribute("links.activated", r.links_activated);
  file.set_attribute("links.exhausted", r.links_exhausted);
  file.set_attribute("links.eroded", r.links_eroded);
  file.set_attribute("links.active", r.links_active);
  file.set_attribute("links.max_active", r.max_links_active);
  file.set_attribute("thesis_criteria.active_link", static_cast<long long>(r.thesis_active_link));
  file.set_attribute("thesis_criteria.one_percent_stuck",
                     static_cast<long long>(r.thesis_one_percent));
  file.set_attribute("energy.initial_kinetic", r.initial_kinetic, "J");
  file.set_attribute("energy.final_particle_kinetic", r.final_particle_kinetic, "J");
  file.set_attribute("energy.adhesion_dissipated", r.adhesion_dissipated, "J");
  file.set_attribute("energy.plastic_work", s.energy.plastic_work, "J");
  file.set_attribute("energy.absorbed", s.energy.absorbed, "J");
  file.set_attribute("energy.hourglass", s.energy.hourglass, "J");
  file.set_attribute("energy.eroded", s.energy.eroded, "J");
  file.set_attribute("energy.balance_error", s.energy.balance_error, "-");
  file.set_attribute("wall_seconds", s.wall_seconds, "s");
  file.set_attribute("max_temperature", r.max_temperature, "K");
  file.set_attribute("max_plastic_strain", r.max_plastic_strain, "-");
  file.set_attribute("flattening_ratio", r.flattening_ratio, "-");
  file.set_attribute("penetration_depth", r.penetration_depth, "m");
  file.set_attribute("hold_time", r.hold_time, "s");
  file.set_attribute("max_time", r.max_time, "s");
  file.set_attribute("end_time_rule", r.adaptive ? "adaptive" : "fixed");
  file.set_attribute("model.name", name_or_empty(r.model));
  file.set_attribute("model.why", r.why);
}

}  // namespace splat
