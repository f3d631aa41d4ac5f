// Steinberg-Guinan flow stress (Steinberg, Cochran & Guinan 1980, J. Appl.
// Phys. 51, 1498; parameter sets in Steinberg, UCRL-MA-106439, 1996), a rate-independent law for
// strain rates above about 1e5 /s, where the flow stress of metals no longer rises with rate:
//
//   sigma_y = min(Y0 (1 + beta (eps_i + eps_p))^n, Y_max) G(P, T) / G0,
//   G(P, T) / G0 = max(0, 1 + A P / eta^(1/3) - B (T - T_ref)),
//
// P the pressure (positive in compression), eta = rho / rho0 = 1 / J, eps_i
// the initial equivalent plastic strain, T_ref the 300 K at which G0 and Y0
// are stated; Y scales with G (the paper takes Y'_P / Y0 = G'_P / G0). In
// tension (P < 0, eta < 1) the same linear form holds, as in the paper and
// in Uintah's SCGShear: the strength falls (zinc: 6 % at -1 GPa); the clamp
// at 0 keeps it from turning negative however hot or stretched the point.
// The pressure and eta are those of the point at the start of the step
// (staggered, as T): the return holds them fixed. As in the other laws: no
// strength at or above T_melt (Steinberg's T_m0, the melting temperature at
// rho0), and with thermal softening off T is T_ref. The rate switch has
// nothing to act on.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "solver/material/model_switches.hpp"
#include "solver/material/strength_law.hpp"

namespace splat {

struct SteinbergGuinanParams {
  static constexpr const char* model = "steinberg-guinan";
  static constexpr bool pressure_dependent = true;
  double Y0 = 0.0;         // yield stress at eps_p = 0, T_ref and P = 0, Pa
  double Y_max = 0.0;      // cap of the work-hardened yield stress, Pa
  double beta = 0.0;       // hardening constant, -
  double n = 0.0;          // hardening exponent, -
  double eps_i = 0.0;      // initial equivalent plastic strain, -
  double A = 0.0;          // pressure coefficient of G / G0, G'_P / G0, 1/Pa (1/Mbar * 1e-11)
  double B = 0.0;          // temperature coefficient of G / G0, -G'_T / G0, 1/K
  double T_ref = 300.0;    // temperature of G0 and Y0, K
  double T_melt = 1000.0;  // melting temperature at rho0, K

  static constexpr std::array<LawField<SteinbergGuinanParams>, 9> fields() {
    using P = SteinbergGuinanParams;
    return {{{"Y0", &P::Y0, Quantity::yield_stress},
             {"Y_max", &P::Y_max, Quantity::yield_stress},
             {"beta", &P::beta, Quantity::dimensionless},
             {"n", &P::n, Quantity::dimensionless},
             {"eps_i", &P::eps_i, Quantity::dimensionless},
             {"A", &P::A, Quantity::inverse_pressure},
             {"B", &P::B, Quantity::inverse_temperature},
             {"T_ref", &P::T_ref, Quantity::room_temperature},
             {"T_melt", &P::T_melt, Quantity::melting_temperature}}};
  }
};

// The law has no reference rate; 1/s is what the damage laws are given.
inline StrengthReferences strength_references(const SteinbergGuinanParams& sg) {
  return {1.0, sg.T_ref, sg.T_melt};
}

// Flow stress and its partial derivatives at (eps_p, eps_dot_p, T) and the
// point's pressure state; the rate slope is zero, the strain slope zero where
// Y_max caps the hardening.
inline FlowStress flow_stress(const SteinbergGuinanParams& sg, const ModelSwitches& sw,
                              double eps_p, double /*eps_dot_p*/, double T,
                              const PressureState& state) {
  const double temp = sw.thermal_softening ? T : sg.T_ref;
  if (temp >= sg.T_melt) return {0.0, 0.0, 0.0};
  const double shear = std::max(
      0.0, 1.0 + sg.A * state.P / std::cbrt(state.eta) - sg.B * (temp - sg.T_ref));  // G / G0
  const double base = 1.0 + sg.beta * (sg.eps_i + std::max(eps_p, 0.0));
  const double hardened = sg.Y0 * std::pow(base, sg.n);
  if (hardened >= sg.Y_max) return {sg.Y_max * shear, 0.0, 0.0};
  const double slope = sg.n * sg.beta * hardened / base;
  return {hardened * shear, slope * shear, 0.0};
}

}  // namespace splat
