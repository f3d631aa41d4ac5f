#include "solver/adhesion/cohesive_law.hpp"

#include <algorithm>
#include <cmath>

namespace splat {

const char* to_string(LinkState s) {
  switch (s) {
    case LinkState::none:
      return "none";
    case LinkState::contact:
      return "contact";
    case LinkState::active:
      return "active";
    case LinkState::exhausted:
      return "exhausted";
    case LinkState::eroded:
      return "eroded";
  }
  return "none";
}

namespace {

// Budget charge of impulse I: the work clamped at 0 plus the stored energy.
double link_charge(const LinkKinematics& k, double I, double dt) {
  const double g_after = k.g_free - k.h * I;
  const double dW = std::max(0.5 * I * (k.g_prev + g_after), 0.0);
  const double F = I / dt;
  return dW + 0.5 * k.compliance * F * F;
}

}  // namespace

CohesiveStep cohesive_step(const AdhesionParams& p, double area, double work_done,
                           const LinkKinematics& k, double dt, double wanted) {
  CohesiveStep out;
  if (!(k.g_free > 0.0) || !(k.h > 0.0) || !(dt > 0.0)) return out;
  const double I_hold = k.g_free / k.h;
  const double I_cap = max_tension(p, area) * dt;  // +inf * dt = +inf without a cap
  double I = std::clamp(std::min(wanted, I_hold), 0.0, std::min(I_hold, I_cap));
  const double W_rem = std::max(work_budget(p, area) - work_done, 0.0);
  if (link_charge(k, I, dt) >= W_rem) {
    // The charge is 0 at I = 0 and continuous: bisect for the largest
    // impulse that keeps it within the remaining budget.
    double lo = 0.0, hi = I;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (link_charge(k, mid, dt) <= W_rem ? lo : hi) = mid;
    }
    I = lo;
    out.work = W_rem;
    out.exhausted = true;
  } else {
    const double g_after = k.g_free - k.h * I;
    out.work = std::max(0.5 * I * (k.g_prev + g_after), 0.0);
  }
  out.impulse = I;
  const double F = I / dt;
  out.stored = 0.5 * k.compliance * F * F;
  return out;
}

}  // namespace splat
