#include "solver/core/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "solver/common/parallel.hpp"
#include "solver/core/model_builder.hpp"
#include "solver/core/simulation_impl.hpp"
#include "solver/fe/heat_conduction.hpp"
#include "solver/io/result_file.hpp"
#include "solver/scene/velocity_history.hpp"

namespace splat {

Simulation::Simulation(const Scene& scene, nlohmann::json resolved_scene, SimulationOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->scene = scene;
  impl_->resolved = std::move(resolved_scene);
  impl_->options = std::move(options);
  impl_->model = build_model(scene);
  if (scene.impact)
    impl_->impact.emplace(*scene.impact, impl_->model, scene.time.end_time,
                          scene.time.energy_balance_limit);
}

Simulation::~Simulation() = default;

namespace {
// Nodes per block of the node loops (stages 1, 4 and the kinetic energy),
// and the node count from which they run in parallel.
constexpr std::size_t node_block = 1024;
constexpr std::size_t min_parallel_nodes = 4096;
// The same for the elements' energy sums and the absorbing faces.
constexpr std::size_t element_block = 1024;
constexpr std::size_t min_parallel_elements = 4096;
constexpr std::size_t face_block = 128;
constexpr std::size_t min_parallel_faces = 256;
}  // namespace

const NodeSet& Simulation::nodes() const {
  return impl_->model.nodes;
}
const std::vector<FeBody>& Simulation::bodies() const {
  return impl_->model.bodies;
}
const std::vector<SphBody>& Simulation::sph_bodies() const {
  return impl_->model.sph_bodies;
}
bool Simulation::axisymmetric() const {
  return impl_->model.axisymmetric;
}

namespace {

// Velocity update of a node with dashpot matrix C, its force at the
// mid-point of the update: (m I + dt C / 2) v = m v_old + dt f - dt C v_old / 2.
Vec3 dashpot_update(double m, const Vec3& v_old, const Vec3& f, const Mat3& C, double dt) {
  const Mat3 A = m * Mat3::Identity() + (0.5 * dt) * C;
  return A.inverse() * (m * v_old + dt * f - (0.5 * dt) * (C * v_old));
}

}  // namespace

// Stage 1: central-difference velocity update, then velocity constraints and
// rigid walls. The work of the constraint reactions R = m (v - v_free) / dt
// over the coming displacement dt v is booked as external (or wall) work;
// in the first step, where a constraint sets the velocity (a jump from the
// initial velocity), the kinetic energy change of that jump is.
// Nodes of absorbing faces take their dashpot force -C v at the mid-point of
// the update (trapezoidal rule): (m I + dt C / 2) v_new = m v_old + dt f -
// dt C v_old / 2. Unconditionally stable, where the force on the old
// velocity is stable only for dt C / m < 2 and, with the element stiffness,
// blew up a uniform 3D mesh at the default stability coefficient; the
// absorbed energy dt v_mid . C v_mid is what the dashpot takes out.
void Simulation::Impl::update_velocities(bool first) {
  set_driven_velocities();
  NodeSet& n = model.nodes;
  const double dt_v = first ? 0.5 * dt_half : 0.5 * (dt_half_prev + dt_half);
  const std::size_t count = n.size();
  const Vec3 sph_power = sph_dissipative_power();
  const bool damped = !damped_slot.empty();
  const Vec2 works = block_sum(
      count, node_block, min_parallel_nodes, Vec2(Vec2::Zero()),
      [&](std::size_t lo, std::size_t hi) {
        double work = 0.0, absorbed = 0.0;
        for (std::size_t i = lo; i < hi; ++i) {
          const double m = n.mass[i];
          if (m <= 0.0) continue;  // node of eroded elements only
          const Vec3 v_old = n.v[i];
          const int slot = damped ? damped_slot[i] : -1;
          const Mat3* C = slot >= 0 ? &node_damping[static_cast<std::size_t>(slot)] : nullptr;
          Vec3 v = C ? dashpot_update(m, v_old, n.f[i], *C, dt_v) : v_old + (dt_v / m) * n.f[i];
          const std::uint8_t mask = model.constraint_mask[i];
          if (mask != 0) {
            const Vec3 v_free = v;
            for (int c = 0; c < 3; ++c) {
              if (mask & (1u << c)) v[c] = model.constraint_value[i][c];
            }
            // The constraint's impulse over the update: what it adds to m v
            // beyond the forces (and the dashpot's mid-point force).
            const Vec3 impulse =
                C ? Vec3(m * (v - v_old) - dt_v * (n.f[i] - *C * (0.5 * (v_old + v))))
                  : Vec3(m * (v - v_free));
            // The first step sets the prescribed velocity, a jump from the
            // initial one where they differ: the constraint's impulse makes
            // the kinetic energy change m dv (v_free + v) / 2 (as a node
            // landing on a wall).
            work +=
                first ? 0.5 * m * (v - v_free).dot(v + v_free) : impulse.dot(v) * dt_half / dt_v;
          }
          if (C) {
            const Vec3 v_mid = 0.5 * (v_old + v);
            absorbed += dt_v * v_mid.dot(*C * v_mid);
          }
          n.v[i] = v;
        }
        return Vec2(work, absorbed);
      });
  const double ext_work = works.x();
  energy.absorbed += works.y() * scale();
  double wall_work = 0.0;
  // A node the wall held in the last step books the reaction's work over the
  // coming displacement, as the constraints above; a node landing on the wall
  // in this step makes a node-level plastic impact and books the kinetic
  // energy it loses, m dv (v_before + v_after) / 2 along the normal (as the
  // Lagrange contact does, contact_interface.hpp).
  for (RigidWall& w : model.walls) {
    w.held.resize(w.nodes.size(), 0);
    for (std::size_t k = 0; k < w.nodes.size(); ++k) {
      const int i = w.nodes[k];
      const double m = n.mass[i];
      const double v_before = n.v[i].dot(w.normal);
      const double gap = (n.x[i] - w.point).dot(w.normal) + dt_half * v_before;
      if (m <= 0.0 || !(gap < 0.0)) {
        w.held[k] = 0;
        continue;
      }
      const double dv = -gap / dt_half;  // lands the node on the wall
      n.v[i] += dv * w.normal;
      const double v_after = v_before + dv;
      wall_work +=
          w.held[k] ? m * dv * v_after * dt_half / dt_v : m * dv * 0.5 * (v_before + v_after);
      w.held[k] = 1;
    }
  }
  energy.external_work += ext_work * scale();
  energy.wall_work += wall_work * scale();
  for (ContactInterface& c : model.contacts) c.book_penalty_work(n, dt_v);
  book_sph_dissipation(sph_power, dt_v);
}

// Stage 1, first: the prescribed velocity of the nodes driven by a table is
// the table's mean over the coming step [t_n, t_n + dt], so that x_{n+1} =
// x_n + dt v_{n+1/2} moves them by the table's exact displacement.
void Simulation::Impl::set_driven_velocities() {
  for (const DrivenSet& d : model.driven) {
    const Vec3 v = history_mean_velocity(d.history, time, dt_half);
    for (const int i : d.nodes) {
      for (int c = 0; c < 3; ++c) {
        if (d.mask & (1u << c)) model.constraint_value[static_cast<std::size_t>(i)][c] = v[c];
      }
    }
  }
}

// Stage 2.
void Simulation::Impl::predict_positions() {
  NodeSet& n = model.nodes;
  const std::size_t count = n.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < count; ++i) n.x[i] += dt_half * n.v[i];
}

// Stage 3: Lagrange-multiplier contact on the predicted positions.
void Simulation::Impl::contact_constraints() {
  for (ContactInterface& c : model.contacts) {
    if (c.settings().method == ContactMethod::lagrange) {
      c.lagrange_step(model.nodes, model.constraint_mask, dt_half, model.bodies, model.sph_bodies);
    }
  }
}

// Stage 4. Returns false when the run must stop (reason in s).
bool Simulation::Impl::internal_forces(RunSummary& s) {
  NodeSet& n = model.nodes;
  for_each_block(n.size(), node_block, min_parallel_nodes,
                 [&](std::size_t first, std::size_t last) {
                   std::fill(n.f.begin() + static_cast<std::ptrdiff_t>(first),
                             n.f.begin() + static_cast<std::ptrdiff_t>(last), Vec3::Zero());
                 });
  dt_stable = std::numeric_limits<double>::infinity();
  for (FeBody& body : model.bodies) {
    FeStepResult r = fe_internal_forces(body, n, dt_half);
    dt_stable = std::min({dt_stable, r.dt_stable, fe_conduct_heat(body, n, dt_half)});
    energy.hourglass += r.hourglass_power * dt_half * scale();
    energy.artificial_viscosity += r.viscosity_power * dt_half * scale();
    max_return_iterations = std::max(max_return_iterations, r.max_return_iterations);
    for (int e : r.to_erode) {
      const ErodedEnergy er = erode_element(body, n, e);
      energy.eroded += (er.internal + er.kinetic) * scale();
    }
    if (!r.to_erode.empty()) {
      for (ContactInterface& c : model.contacts) c.follow_erosion(model.bodies);
    }
    if (r.return_failed) {
      s.outcome = RunOutcome::unstable;
      s.stop_reason = StopReason::return_mapping;
      s.reason =
          "the return mapping of the strength law did not converge in body '" + body.name + "'";
      return false;
    }
    if (r.inverted > 0) {
      s.outcome = RunOutcome::unstable;
      s.stop_reason = StopReason::element_inverted;
      s.reason = std::to_string(r.inverted) + " element(s) of body '" + body.name +
                 "' inverted (non-positive volume) and erosion is off";
      return false;
    }
  }
  return sph_internal_forces_all(s);
}

// Dashpot matrix of an absorbing face on each of its nodes (stage 5).
FaceDamping absorbing_face_damping(const AbsorbingFace& face, const NodeSet& n) {
  FaceDamping out;
  Vec3 normal;
  double area;
  if (face.count == 2) {  // axisymmetric segment a -> b, outward normal on the right
    const Vec3 a = n.x[face.nodes[0]], b = n.x[face.nodes[1]];
    const Vec3 d = b - a;
    const double len = d.norm();
    if (len <= 0.0) return out;
    normal = Vec3(d.y(), -d.x(), 0.0) / len;
    area = len * 0.5 * (a.x() + b.x());  // per radian
  } else {
    const Vec3& x0 = n.x[face.nodes[0]];
    const Vec3& x1 = n.x[face.nodes[1]];
    const Vec3& x2 = n.x[face.nodes[2]];
    const Vec3& x3 = n.x[face.nodes[3]];
    const Vec3 av = 0.5 * (x2 - x0).cross(x3 - x1);
    area = av.norm();
    if (area <= 0.0) return out;
    normal = av / area;
  }
  const Mat3 nn = normal * normal.transpose();
  out.c = (area / face.count) * (face.rho_cp * nn + face.rho_cs * (Mat3::Identity() - nn));
  out.live = true;
  return out;
}

// Slots of the nodes of absorbing faces (once, before the first step).
void Simulation::Impl::setup_absorbing() {
  damped_slot.clear();
  node_damping.clear();
  if (model.absorbing.empty()) return;
  damped_slot.assign(model.nodes.size(), -1);
  int slots = 0;
  for (const AbsorbingFace& face : model.absorbing) {
    for (int k = 0; k < face.count; ++k) {
      int& slot = damped_slot[static_cast<std::size_t>(face.nodes[k])];
      if (slot < 0) slot = slots++;
    }
  }
  node_damping.assign(static_cast<std::size_t>(slots), Mat3::Zero());
}

// The dashpot matrices at the current positions: each face's in parallel,
// then summed on its nodes face by face (faces share nodes), in face order.
void Simulation::Impl::absorbing_damping() {
  const std::size_t faces = model.absorbing.size();
  if (faces == 0) return;
  face_damping.resize(faces);
  for_each_block(faces, face_block, min_parallel_faces, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t k = lo; k < hi; ++k) {
      face_damping[k] = absorbing_face_damping(model.absorbing[k], model.nodes);
    }
  });
  std::fill(node_damping.begin(), node_damping.end(), Mat3::Zero());
  for (std::size_t k = 0; k < faces; ++k) {
    if (!face_damping[k].live) continue;
    const AbsorbingFace& face = model.absorbing[k];
    for (int j = 0; j < face.count; ++j) {
      node_damping[static_cast<std::size_t>(damped_slot[face.nodes[j]])] += face_damping[k].c;
    }
  }
}

// Stage 5: penalty contact forces, then the dashpot matrices of the viscous
// absorbing boundaries at x_{n+1}, C = A (rho c_p n n^T + rho c_s (I - n n^T))
// on each node's share A of a boundary face (Lysmer & Kuhlemeyer 1969),
// applied in the next velocity update (stage 1).
void Simulation::Impl::boundary_forces() {
  NodeSet& n = model.nodes;
  for (ContactInterface& c : model.contacts) {
    if (c.settings().method == ContactMethod::penalty) {
      c.penalty_forces(n, model.constraint_mask, dt_half);
    }
  }
  absorbing_damping();
  sph_boundary_forces();
}

void Simulation::Impl::compute_energies() {
  const NodeSet& n = model.nodes;
  const double kinetic = block_sum(n.size(), node_block, min_parallel_nodes, 0.0,
                                   [&](std::size_t first, std::size_t last) {
                                     double sum = 0.0;
                                     for (std::size_t i = first; i < last; ++i)
                                       sum += 0.5 * n.mass[i] * n.v[i].squaredNorm();
                                     return sum;
                                   });
  double internal = 0.0, plastic = 0.0;
  for (const FeBody& b : model.bodies) {
    const Vec2 sums = block_sum(b.num_elements(), element_block, min_parallel_elements,
                                Vec2(Vec2::Zero()), [&](std::size_t lo, std::size_t hi) {
                                  Vec2 sum = Vec2::Zero();
                                  for (std::size_t e = lo; e < hi; ++e) {
                                    if (!b.active[e]) continue;
                                    sum +=
                                        b.volume0[e] * Vec2(b.state[e].e, b.state[e].plastic_work);
                                  }
                                  return sum;
                                });
    internal += sums.x();
    plastic += sums.y();
  }
  sph_energies(internal, plastic);
  energy.kinetic = kinetic * scale();
  energy.internal = internal * scale();
  energy.plastic_work = plastic * scale();
  energy.contact_work = 0.0;
  energy.contact_stored = 0.0;
  energy.adhesion = 0.0;
  for (const ContactInterface& c : model.contacts) {
    energy.contact_work += c.stats().work;
    energy.contact_stored += c.stats().stored;
    energy.adhesion += c.stats().adhesion_work;
  }
  const double total = energy.kinetic + energy.internal + energy.hourglass +
                       energy.artificial_viscosity + energy.absorbed + energy.eroded;
  // Relative to the energy the run was given: the initial energy plus the
  // work put in by prescribed velocities (a body driven from rest has no
  // initial energy).
  const double reference =
      std::max(energy.initial_total + std::max(energy.external_work, 0.0), 1e-300);
  energy.balance_error = (total - energy.initial_total - energy.external_work - energy.wall_work -
                          energy.contact_work) /
                         reference;
}

std::optional<std::pair<RunOutcome, std::string>> Simulation::Impl::checks(
    const std::chrono::steady_clock::time_point& start, std::optional<StopReason>& stop_reason) {
  const TimeSpec& ts = scene.time;
  if (!std::isfinite(energy.kinetic) || !std::isfinite(energy.internal) ||
      !std::isfinite(dt_stable)) {
    stop_reason = StopReason::non_finite;
    return std::pair{RunOutcome::unstable,
                     "non-finite state (NaN or infinity) at step " + std::to_string(step)};
  }
  // Default floor: a thousandth of the first step. Below it a run would need
  // a thousand times its planned step count, which only a crushed (tangled)
  // element asks for; stopping names the cause instead of running for hours.
  const double dt_floor = ts.min_time_step > 0.0 ? ts.min_time_step : 1e-3 * dt_first;
  if (ts.stability_coefficient * dt_stable < dt_floor) {
    stop_reason = StopReason::time_step_collapse;
    char buf[160];
    std::snprintf(buf, sizeof buf, "time step collapsed to %.3e s (floor %.3e s)",
                  ts.stability_coefficient * dt_stable, dt_floor);
    return std::pair{RunOutcome::unstable, std::string(buf)};
  }
  // Every step for runs given an initial energy; a run driven from rest
  // (no initial energy) books the work of its constraints one step late, a
  // lag that is large against the little work put in at first, and is checked
  // at its end instead (final_energy_check).
  if (std::abs(energy.balance_error) > ts.energy_balance_limit && energy.initial_total > 0.0) {
    stop_reason = StopReason::energy_balance;
    char buf[160];
    std::snprintf(buf, sizeof buf, "energy balance error %.3g above its limit %.3g",
                  energy.balance_error, ts.energy_balance_limit);
    return std::pair{RunOutcome::unstable, std::string(buf)};
  }
  if (options.cancel && options.cancel->load()) {
    stop_reason = StopReason::cancelled;
    return std::pair{RunOutcome::cancelled, std::string("cancelled")};
  }
  if (ts.wall_clock_limit > 0.0) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wall > ts.wall_clock_limit) {
      stop_reason = StopReason::wall_clock_limit;
      char buf[160];
      std::snprintf(buf, sizeof buf, "wall-clock limit of %.1f s reached at t = %.3e s",
                    ts.wall_clock_limit, time);
      return std::pair{RunOutcome::timed_out, std::string(buf)};
    }
  }
  if (step >= ts.max_steps) {
    stop_reason = StopReason::step_limit;
    return std::pair{RunOutcome::timed_out,
                     "step limit of " + std::to_string(ts.max_steps) + " reached"};
  }
  return std::nullopt;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The OpenMP team of a run: options.threads, or OpenMP's default; the
// calling thread's setting is put back when the run ends, whatever count the
// governor left in force.
class ThreadTeam {
 public:
  explicit ThreadTeam(int asked) {
#ifdef _OPENMP
    before_ = omp_get_max_threads();
    if (asked > 0) omp_set_num_threads(asked);
    team_ = omp_get_max_threads();
#else
    (void)asked;
#endif
  }
  ~ThreadTeam() {
    use(before_);
  }
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  int size() const {
    return team_;
  }
  void use(int threads) {
#ifdef _OPENMP
    if (threads != in_force_) omp_set_num_threads(threads);
#endif
    in_force_ = threads;
  }

 private:
  int before_ = 1;
  int team_ = 1;
  int in_force_ = 0;
};

}  // namespace

RunSummary Simulation::run() {
  Impl& s = *impl_;
  RunSummary summary;
  summary.scene = s.scene.name;
  const auto start = Clock::now();
  ThreadTeam team(s.options.threads);
  ThreadGovernor governor(team.size(), s.options.thread_policy, s.options.thread_governor);
  team.use(governor.threads());
  try {
    s.open_output();
    // Initial state: no force yet; the dashpots of the absorbing faces at x_0.
    NodeSet& n = s.model.nodes;
    std::fill(n.f.begin(), n.f.end(), Vec3::Zero());
    s.setup_absorbing();
    s.absorbing_damping();
    // The first step is capped by the closing speed too; the time-step floor
    // stays relative to the elastic bound.
    s.closing_speed = initial_closing_speed(s.model);
    s.dt_stable = initial_time_step_bound(s.model);
    s.dt_first = s.scene.time.stability_coefficient * s.dt_stable;
    s.dt_stable = std::min(s.dt_stable, closing_speed_time_step_bound(s.model, s.closing_speed));
    s.dt_half = s.scene.time.stability_coefficient * s.dt_stable;
    s.compute_energies();
    s.energy.initial_total = s.energy.kinetic + s.energy.internal;
    s.energy.balance_error = 0.0;
    s.write_history();
    s.write_snapshot();

    const double end_time = s.scene.time.end_time;
    bool stopped = false;
    while (!stopped) {
      const auto step_start = Clock::now();
      if (s.time + s.dt_half > end_time) s.dt_half = end_time - s.time;
      s.update_velocities(s.step == 0);
      s.predict_positions();
      s.contact_constraints();
      if (!s.internal_forces(summary)) {
        stopped = true;
      } else {
        s.boundary_forces();
        // The next step's bound, closing speed included, so that the
        // time-step floor (checks) sees the step the run would take: an
        // element crushed to a sliver caps it there, not in the CFL bound.
        s.dt_stable =
            std::min(s.dt_stable, closing_speed_time_step_bound(s.model, s.closing_speed));
      }
      s.time += s.dt_half;
      ++s.step;
      s.compute_energies();
      if (!stopped) {
        if (auto stop = s.checks(start, summary.stop_reason)) {
          summary.outcome = stop->first;
          summary.reason = stop->second;
          stopped = true;
        }
      }
      if (!stopped && s.impact) {
        s.verdict = s.impact->observe(s.time, s.model);
        if (s.verdict && s.scene.impact->adaptive_end) {
          summary.stop_reason = StopReason::verdict_settled;
          stopped = true;
        }
      }
      const bool at_end = s.time >= end_time * (1.0 - 1e-12);
      if (at_end && !stopped) {
        summary.outcome = RunOutcome::finished;
        summary.stop_reason = StopReason::end_time;
        summary.reason = "reached the end time";
        stopped = true;
      }
      team.use(governor.step_done(seconds_since(step_start)));  // output not timed
      if (stopped || s.time >= s.next_history_time) s.write_history();
      // A run that stops before its last requested snapshot still leaves its
      // final state in the file.
      s.write_snapshot(stopped);
      s.dt_half_prev = s.dt_half;
      s.dt_half = s.scene.time.stability_coefficient * s.dt_stable;
      if (!s.options.quiet && s.step % 1000 == 0) {
        std::fprintf(stderr, "step %lld t = %.4e s dt = %.3e s E_err = %.2e\n", s.step, s.time,
                     s.dt_half, s.energy.balance_error);
      }
    }
    if (!s.final_energy_check(summary)) s.verdict.reset();
    s.fill_summary(summary);
    if (s.impact) s.impact->finish(summary, s.model, s.verdict);
    if (s.file) {
      if (summary.impact) {
        summary.wall_seconds = seconds_since(start);
        write_impact_attributes(*s.file, summary);
      }
      s.file->set_attribute("outcome", to_string(summary.outcome));
      s.file->set_attribute("reason", summary.reason);
      s.file->set_attribute("stop_reason", name_or_empty(summary.stop_reason));
      s.file->set_attribute("steps", summary.steps);
      s.file->set_attribute("end_time", summary.end_time, "s");
      s.file->close();
    }
  } catch (const std::exception& e) {
    s.fill_summary(summary);
    if (s.impact) s.impact->finish(summary, s.model, std::nullopt);
    summary.outcome = RunOutcome::error;
    summary.stop_reason = StopReason::error;
    summary.reason = e.what();
  }
  summary.threads = governor.use();
  summary.wall_seconds = seconds_since(start);
  return summary;
}

// A run that reached its end time (or a verdict) with the energy balance
// beyond its limit broke somewhere on the way; it must not end `finished`.
// Catches the runs the per-step check leaves out (driven from rest). Returns
// false when the check failed.
bool Simulation::Impl::final_energy_check(RunSummary& s) const {
  const bool own_end =
      s.stop_reason == StopReason::end_time || s.stop_reason == StopReason::verdict_settled;
  const bool energy_given = energy.initial_total + std::max(energy.external_work, 0.0) > 0.0;
  const double limit = scene.time.energy_balance_limit;
  if (!own_end || !energy_given || !(std::abs(energy.balance_error) > limit)) return true;
  s.outcome = RunOutcome::unstable;
  s.stop_reason = StopReason::energy_balance;
  char buf[200];
  std::snprintf(buf, sizeof buf, "energy balance error %.3g above its limit %.3g at the end",
                energy.balance_error, limit);
  s.reason = buf;
  return false;
}

void Simulation::Impl::fill_summary(RunSummary& s) const {
  s.steps = step;
  s.end_time = time;
  s.energy = energy;
  s.bodies.clear();
  const NodeSet& n = model.nodes;
  for (const FeBody& b : model.bodies) {
    BodySummary bs;
    bs.name = b.name;
    bs.elements = static_cast<long long>(b.num_elements());
    bs.nodes = static_cast<long long>(b.node_end - b.node_begin);
    Vec3 momentum = Vec3::Zero();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    double mass = 0.0, kinetic = 0.0;
    for (std::size_t i = b.node_begin; i < b.node_end; ++i) {
      if (n.mass[i] <= 0.0) continue;
      mass += n.mass[i];
      momentum += n.mass[i] * n.v[i];
      kinetic += 0.5 * n.mass[i] * n.v[i].squaredNorm();
      lo = lo.cwiseMin(n.x[i]);
      hi = hi.cwiseMax(n.x[i]);
    }
    bs.mass = mass * scale();
    bs.kinetic_energy = kinetic * scale();
    bs.centroid_velocity = centroid_velocity(model, momentum, mass);
    if (!(mass > 0.0)) {  // every element eroded: no extent
      lo = hi = Vec3::Zero();
    }
    if (model.axisymmetric) {
      // The body of revolution spans -r_max..r_max in x and y.
      bs.extent_min = Vec3(-hi.x(), -hi.x(), lo.y());
      bs.extent_max = Vec3(hi.x(), hi.x(), hi.y());
    } else {
      bs.extent_min = lo;
      bs.extent_max = hi;
    }
    for (std::size_t e = 0; e < b.num_elements(); ++e) {
      if (!b.active[e]) {
        ++bs.eroded_elements;
        continue;
      }
      bs.max_plastic_strain = std::max(bs.max_plastic_strain, b.state[e].eps_p);
      bs.max_temperature = std::max(bs.max_temperature, b.state[e].T);
    }
    s.bodies.push_back(bs);
  }
  sph_summaries(s);
  s.interfaces.clear();
  for (const ContactInterface& c : model.contacts) {
    const ContactStats& st = c.stats();
    InterfaceSummary is;
    is.master = c.master_body();
    is.slave = c.slave_body();
    is.method = c.settings().method == ContactMethod::lagrange ? "lagrange" : "penalty";
    is.friction = c.settings().friction;
    is.work = st.work;
    is.stored = st.stored;
    is.dissipated = -st.work - st.stored;
    is.pairs_in_contact = st.in_contact;
    is.max_pairs_in_contact = st.max_in_contact;
    is.nodes_ever_in_contact = st.ever_in_contact;
    is.max_solver_iterations = st.max_iterations;
    is.max_solver_residual = st.max_residual;
    is.unconverged_solves = st.unconverged;
    is.max_penetration = st.max_penetration;
    is.adhesion = c.settings().adhesion.has_value();
    is.adhesion_work = st.adhesion_work;
    is.links_activated = st.links_activated;
    is.links_exhausted = st.links_exhausted;
    is.links_eroded = st.links_eroded;
    is.links_active = st.links_active;
    is.max_links_active = st.max_links_active;
    is.bonded_area = st.bonded_area;
    is.max_bonded_area = st.max_bonded_area;
    s.interfaces.push_back(is);
  }
  s.hdf5_path = h5_path.empty() ? std::string() : h5_path.string();
  // The .xmf describes the field snapshots; without any it is not written.
  s.xdmf_path =
      h5_path.empty() || snapshots_written == 0 ? std::string() : xmf_path_for(h5_path).string();
}

}  // namespace splat
