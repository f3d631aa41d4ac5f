// Zerilli-Armstrong flow stress of FCC metals (Zerilli & Armstrong 1987,
// J. Appl. Phys. 61, 1816), from thermally activated dislocation motion
// through forest dislocations:
//
//   sigma_y = C0 + C2 eps_p^(1/2) exp(-C3 T + C4 T ln(eps_dot_p / eps_dot_0)),
//
// C0 = Delta sigma_G' + k l^(-1/2) the athermal stress with the Hall-Petch
// term, T the absolute temperature, eps_dot_0 = 1/s the unit of the paper's
// ln(eps_dot). Two clamps of ours, as in the Johnson-Cook law: rates below
// eps_dot_0 count as eps_dot_0 (so the zero-rate strength the yield test of
// an elastic step uses is finite), and there is no strength at or above
// T_melt. With thermal softening off T is T_ref throughout; with rate
// hardening off the rate is eps_dot_0. Strength rises with strain and rate
// and falls with temperature, as the general radial return
// (strength_model.hpp) needs.
#pragma once

#include <array>

#include "solver/material/model_switches.hpp"
#include "solver/material/strength_law.hpp"

namespace splat {

struct ZerilliArmstrongParams {
  static constexpr const char* model = "zerilli-armstrong";
  double C0 = 0.0;         // athermal stress plus Hall-Petch term, Pa
  double C2 = 0.0;         // strain-hardening amplitude, Pa
  double C3 = 0.0;         // thermal softening coefficient, 1/K
  double C4 = 0.0;         // rate-temperature coupling coefficient, 1/K
  double eps_dot_0 = 1.0;  // unit rate of ln(eps_dot) and lowest rate counted, 1/s
  double T_ref = 300.0;    // reference (room) temperature, K
  double T_melt = 1000.0;  // melting temperature, K

  static constexpr std::array<LawField<ZerilliArmstrongParams>, 7> fields() {
    using P = ZerilliArmstrongParams;
    return {{{"C0", &P::C0, Quantity::yield_stress},
             {"C2", &P::C2, Quantity::hardening_stress},
             {"C3", &P::C3, Quantity::inverse_temperature},
             {"C4", &P::C4, Quantity::inverse_temperature},
             {"eps_dot_0", &P::eps_dot_0, Quantity::rate},
             {"T_ref", &P::T_ref, Quantity::room_temperature},
             {"T_melt", &P::T_melt, Quantity::melting_temperature}}};
  }
};

inline StrengthReferences strength_references(const ZerilliArmstrongParams& za) {
  return {za.eps_dot_0, za.T_ref, za.T_melt};
}

// Flow stress and its partial derivatives at (eps_p, eps_dot_p, T); the
// slope in eps_p is unbounded at eps_p = 0 (C2 > 0). No pressure dependence.
FlowStress flow_stress(const ZerilliArmstrongParams& za, const ModelSwitches& sw, double eps_p,
                       double eps_dot_p, double T, const PressureState& state);

}  // namespace splat
