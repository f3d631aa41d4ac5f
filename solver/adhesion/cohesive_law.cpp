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

CohesiveStep cohesive_step(const AdhesionParams& p, double area, double work_done, double g_free,
                           double h, double dt, double wanted) {
  CohesiveStep out;
  if (!(g_free > 0.0) || !(h > 0.0)) return out;
  const double I_hold = g_free / h;
  const double I_cap = max_tension(p, area) * dt;  // +inf * dt = +inf without a cap
  double I = std::clamp(std::min(wanted, I_hold), 0.0, std::min(I_hold, I_cap));
  // dW = I (g_free + g_after) / 2 with g_after = g_free - h I.
  double dW = I * (g_free - 0.5 * h * I);
  const double W_rem = std::max(work_budget(p, area) - work_done, 0.0);
  if (dW >= W_rem) {
    // Smaller root of I g_free - h I^2 / 2 = W_rem, in the cancellation-free
    // form; the discriminant is positive because W_rem <= dW <= g_free^2 / (2h).
    const double disc = std::max(g_free * g_free - 2.0 * h * W_rem, 0.0);
    I = std::min(I, 2.0 * W_rem / (g_free + std::sqrt(disc)));
    dW = W_rem;
    out.exhausted = true;
  }
  out.impulse = I;
  out.work = dW;
  return out;
}

}  // namespace splat
