// The strength law of a material: one of the laws below, each in its own
// header with its named parameters, units and equation. A law offers
//   - a parameter struct P with P::model (its "model" name in the material
//     schema) and P::fields() (its parameters, strength_law.hpp),
//   - strength_references(P) and
//   - flow_stress(P, switches, eps_p, eps_dot_p, T, pressure_state) with the
//     partial derivatives in eps_p and eps_dot_p, non-decreasing in both
//     (and P::pressure_dependent if it uses the PressureState);
// the general point update (point_update.cpp) then runs it through
// law_return below. Johnson-Cook has its own return and SIMD fast path
// (johnson_cook.hpp, point_update_fast.hpp). To add a law: its header, and
// its parameter struct in StrengthModel.
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>

#include "solver/material/johnson_cook.hpp"
#include "solver/material/model_switches.hpp"
#include "solver/material/preston_tonks_wallace.hpp"
#include "solver/material/steinberg_guinan.hpp"
#include "solver/material/strength_law.hpp"
#include "solver/material/zerilli_armstrong.hpp"

namespace splat {

using StrengthModel = std::variant<JohnsonCookParams, ZerilliArmstrongParams,
                                   PrestonTonksWallaceParams, SteinbergGuinanParams>;

// The "model" name of the law (johnson-cook, zerilli-armstrong, ...).
inline const char* strength_model_name(const StrengthModel& s) {
  return std::visit([](const auto& law) { return law.model; }, s);
}

inline StrengthReferences strength_references(const StrengthModel& s) {
  return std::visit([](const auto& law) { return strength_references(law); }, s);
}

// The flow stress of the material's law; at no pressure and rho = rho0
// unless `state` is given.
inline FlowStress flow_stress(const StrengthModel& s, const ModelSwitches& sw, double eps_p,
                              double eps_dot_p, double T, const PressureState& state = {}) {
  return std::visit(
      [&](const auto& law) { return flow_stress(law, sw, eps_p, eps_dot_p, T, state); }, s);
}

// Flow stress with no plastic strain at the reference rate and temperature,
// no pressure and rho = rho0: the initial yield stress, Pa (A for Johnson-Cook, C0 for
// Zerilli-Armstrong).
inline double initial_yield_stress(const StrengthModel& s) {
  const StrengthReferences r = strength_references(s);
  return flow_stress(s, ModelSwitches{}, 0.0, r.eps_dot_0, r.T_ref).value;
}

struct LawReturn {
  double delta_eps_p = 0.0;  // plastic strain increment, -
  double sigma_y = 0.0;      // damaged flow stress at the solution, Pa
  int iterations = 0;        // Newton or bisection iterations used
  bool converged = true;
};

// Radial return for von Mises plasticity with any law: finds dp >= 0 with
//   g(dp) = q_trial - 3 G_d dp - keep sigma_y(eps_p + dp, dp / dt, T, state) = 0,
// keep = 1 - D, T and the pressure state those at the start of the step
// (staggered update), G_d the damaged shear modulus. The caller found
// g(0) > 0; g(q_trial / 3 G_d) <= 0 and g is strictly decreasing (sigma_y is
// non-decreasing in strain and rate), so the root is unique and bracketed.
// Newton steps are kept inside the shrinking bracket; a step that would leave
// it, or an unbounded slope (eps_p^(1/2) at eps_p = 0), bisects instead.
template <class Law>
LawReturn law_return(const Law& law, const ModelSwitches& sw, double q_trial, double G_d,
                     double keep, double eps_p, double dt, double T, const PressureState& state) {
  constexpr int max_iterations = 200;
  const double three_g = 3.0 * G_d;
  LawReturn r;
  double lo = 0.0, hi = q_trial / three_g;
  const double tol_g = 1e-11 * q_trial;
  double dp = 0.5 * hi;
  r.converged = false;
  for (int it = 1; it <= max_iterations; ++it) {
    r.iterations = it;
    const FlowStress f = flow_stress(law, sw, eps_p + dp, dp / dt, T, state);
    r.sigma_y = keep * f.value;
    const double g = q_trial - three_g * dp - r.sigma_y;
    (g > 0.0 ? lo : hi) = dp;
    if (std::abs(g) <= tol_g || hi - lo <= 1e-14 * hi) {
      r.converged = true;
      break;
    }
    const double slope = -three_g - keep * (f.d_eps_p + f.d_rate / dt);
    const double next = dp - g / slope;
    dp = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  r.delta_eps_p = dp;
  return r;
}

}  // namespace splat
