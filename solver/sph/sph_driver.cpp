#include "solver/sph/sph_driver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace splat {

void SphDriver::prescribe(std::size_t g, std::uint8_t mask, const Vec3& value) {
  mask_.resize(nodes.size(), 0);
  value_.resize(nodes.size(), Vec3::Zero());
  mask_[g] |= mask;
  for (int c = 0; c < 3; ++c) {
    if (mask & (1u << c)) value_[g][c] = value[c];
  }
}

long long SphDriver::reference_updates() const {
  long long n = 0;
  for (const SphBody& b : bodies) n += b.reference_updates;
  return n;
}

SphOutcome SphDriver::compute_forces(double dt) {
  for (Vec3& f : nodes.f) f.setZero();
  double dt_min = std::numeric_limits<double>::infinity();
  double visc = 0.0, hg = 0.0, internal = 0.0, absorbed = 0.0;
  for (SphBody& b : bodies) {
    const SphStepResult r = sph_internal_forces(b, nodes, dt);
    if (r.inverted > 0) {
      reason_ = "body '" + b.name + "': " + std::to_string(r.inverted) + " inverted particles";
      return SphOutcome::unstable;
    }
    dt_min = std::min(dt_min, r.dt_stable);
    visc += r.viscosity_power;
    hg += r.hourglass_power;
    internal += sph_internal_energy(b);
  }
  for (const SphAbsorbing& a : absorbing) absorbed += apply_sph_absorbing(a, nodes);
  energy_.viscosity += visc * dt;
  energy_.hourglass += hg * dt;
  energy_.absorbed += absorbed * dt;
  energy_.internal = internal;
  for (const Vec3& f : nodes.f) {
    if (!f.allFinite()) {
      reason_ = "non-finite force";
      return SphOutcome::unstable;
    }
  }
  dt_prev_ = dt_;
  dt_ = fixed_dt > 0.0 ? fixed_dt : stability * dt_min;
  if (!(dt_ > 0.0) || !std::isfinite(dt_)) {
    reason_ = "time step collapsed";
    return SphOutcome::unstable;
  }
  return SphOutcome::running;
}

SphOutcome SphDriver::start() {
  mask_.resize(nodes.size(), 0);
  value_.resize(nodes.size(), Vec3::Zero());
  dt_ = 0.0;
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    for (int c = 0; c < 3; ++c) {
      if (mask_[g] & (1u << c)) nodes.v[g][c] = value_[g][c];
    }
  }
  const SphOutcome o = compute_forces(0.0);
  dt_prev_ = 0.0;
  return o;
}

SphOutcome SphDriver::step() {
  const double dt = dt_;
  const double dt_v = steps_ == 0 ? 0.5 * dt : 0.5 * (dt_prev_ + dt);
  double ext = 0.0, wall_work = 0.0, kinetic = 0.0;
  for (std::size_t g = 0; g < nodes.size(); ++g) {
    const double m = nodes.mass[g];
    if (m <= 0.0) continue;
    Vec3 v = nodes.v[g] + (dt_v / m) * nodes.f[g];
    if (mask_[g] != 0) {
      const Vec3 v_free = v;
      for (int c = 0; c < 3; ++c) {
        if (mask_[g] & (1u << c)) v[c] = value_[g][c];
      }
      ext += m * (v - v_free).dot(v) * dt / dt_v;
    }
    if (wall) {
      const double gap = (nodes.x[g] - wall->point).dot(wall->normal) + dt * v.dot(wall->normal);
      if (gap < 0.0) {
        const double dv = -gap / dt;
        v += dv * wall->normal;
        wall_work += m * dv * v.dot(wall->normal) * dt / dt_v;
      }
    }
    nodes.v[g] = v;
    nodes.x[g] += dt * v;
    kinetic += 0.5 * m * v.squaredNorm();
  }
  energy_.kinetic = kinetic;
  energy_.external_work += ext;
  energy_.wall_work += wall_work;
  time_ += dt;
  ++steps_;
  return compute_forces(dt);
}

SphOutcome SphDriver::run(double end_time, long long max_steps) {
  while (time_ < end_time * (1.0 - 1e-12) && steps_ < max_steps) {
    if (end_time - time_ < dt_) dt_ = end_time - time_;
    const SphOutcome o = step();
    if (o == SphOutcome::unstable) return o;
  }
  return SphOutcome::finished;
}

}  // namespace splat
