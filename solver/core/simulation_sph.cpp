// SPH side of the time loop (stages 4-6 for SPH bodies): the SPH counterpart
// of the FE element loop, the absorbing layers of SPH bodies, their energy
// terms and their summaries. Particles are nodes of the shared NodeSet, so
// stages 1-3 (update, predict, contact) treat them like FE nodes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "solver/core/model_builder.hpp"
#include "solver/core/simulation_impl.hpp"

namespace splat {

// Stage 4 for SPH bodies. Returns false when the run must stop (reason in s).
bool Simulation::Impl::sph_internal_forces_all(RunSummary& s) {
  NodeSet& n = model.nodes;
  for (SphBody& body : model.sph_bodies) {
    const SphStepResult r = sph_internal_forces(body, n, dt_half);
    dt_stable = std::min(dt_stable, r.dt_stable);
    // A deactivated particle keeps flying (its kinetic energy stays in the
    // balance); its internal energy leaves with it.
    energy.eroded += r.deactivated_energy;
    max_return_iterations = std::max(max_return_iterations, r.max_return_iterations);
    if (r.return_failed) {
      s.outcome = RunOutcome::unstable;
      s.stop_reason = StopReason::return_mapping;
      s.reason =
          "the return mapping of the strength law did not converge in body '" + body.name + "'";
      return false;
    }
    if (r.inverted > 0) {
      s.outcome = RunOutcome::unstable;
      s.stop_reason = StopReason::particle_inverted;
      s.reason =
          std::to_string(r.inverted) + " particle(s) of body '" + body.name + "' have det F <= 0";
      return false;
    }
  }
  return true;
}

// Work of the SPH viscosity and hourglass forces f_n of the last stage 4,
// booked in stage 1 when they change the velocities over dt_v: the
// central-difference kinetic energy change they cause is
//   dt_v f_n . (v_{n-1/2} + v_{n+1/2}) / 2,
// so stage 1 calls this before (v_{n-1/2}) and after (v_{n+1/2}) the update
// and books the mean. (Booking f_n . v_{n+1/2} dt alone, as the body's
// SphStepResult powers do, drifts: for the stiff hourglass forces of a
// vibrating ball it booked 57 % of the initial energy in 10 us while
// kinetic + internal energy changed by 2 %.)
Vec3 Simulation::Impl::sph_dissipative_power() const {
  const NodeSet& n = model.nodes;
  double visc = 0.0, hg = 0.0;
  for (const SphBody& b : model.sph_bodies) {
    const SphEnergySums p = sph_stabiliser_power(b, n);
    visc += p.viscosity;
    hg += p.hourglass;
  }
  return Vec3(visc, hg, 0.0);
}

void Simulation::Impl::book_sph_dissipation(const Vec3& power_before, double dt_v) {
  const Vec3 power_after = sph_dissipative_power();
  energy.artificial_viscosity += 0.5 * (power_before.x() + power_after.x()) * dt_v;
  energy.hourglass += 0.5 * (power_before.y() + power_after.y()) * dt_v;
}

// Stage 5 for SPH bodies: absorbing layers, f = -A (rho c_p v_n n + rho c_s v_t).
void Simulation::Impl::sph_boundary_forces() {
  double power = 0.0;
  for (const SphAbsorbing& a : model.sph_absorbing) power += apply_sph_absorbing(a, model.nodes);
  energy.absorbed += power * dt_half;
}

void Simulation::Impl::sph_energies(double& internal, double& plastic) const {
  for (const SphBody& b : model.sph_bodies) {
    const SphEnergySums e = sph_energy_sums(b);
    internal += e.internal;
    plastic += e.plastic;
  }
}

// Appends the SPH bodies' summaries and puts all bodies in scene order.
void Simulation::Impl::sph_summaries(RunSummary& s) const {
  const NodeSet& n = model.nodes;
  for (const SphBody& b : model.sph_bodies) {
    BodySummary bs;
    bs.name = b.name;
    bs.elements = static_cast<long long>(b.size());  // particles
    bs.nodes = static_cast<long long>(b.size());
    Vec3 momentum = Vec3::Zero();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    double mass = 0.0, kinetic = 0.0;
    for (std::size_t k = 0; k < b.size(); ++k) {
      const std::size_t i = b.node_begin + k;
      if (!b.active[k]) ++bs.eroded_elements;
      if (n.mass[i] <= 0.0) continue;
      mass += n.mass[i];
      momentum += n.mass[i] * n.v[i];
      kinetic += 0.5 * n.mass[i] * n.v[i].squaredNorm();
      lo = lo.cwiseMin(n.x[i]);
      hi = hi.cwiseMax(n.x[i]);
      bs.max_plastic_strain = std::max(bs.max_plastic_strain, b.state[k].eps_p);
      bs.max_temperature = std::max(bs.max_temperature, b.state[k].T);
    }
    bs.mass = mass;
    bs.kinetic_energy = kinetic;
    bs.centroid_velocity = centroid_velocity(model, momentum, mass);
    bs.extent_min = lo;
    bs.extent_max = hi;
    s.bodies.push_back(bs);
  }
  // Scene order: fill_summary wrote the FE bodies first, then these.
  std::vector<BodySummary> ordered;
  const std::size_t fe = model.bodies.size();
  for (const BodyRef& r : model.body_refs)
    ordered.push_back(s.bodies[r.sph ? fe + r.index : r.index]);
  s.bodies = std::move(ordered);
}

}  // namespace splat
