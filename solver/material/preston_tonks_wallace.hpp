// Preston-Tonks-Wallace flow stress (Preston, Tonks & Wallace 2003, J. Appl.
// Phys. 93, 211), built to span quasi-static to overdriven-shock rates
// (1e-3 to 1e12 /s). In stresses normalised by the shear modulus G and the
// homologous temperature T^ = T / T_melt, with the plastic strain psi and
// the rate ratio r = eps_dot_p / (gamma xi_dot), xi_dot = 1/2 (4 pi rho /
// (3 M))^(1/3) (G / rho)^(1/2) the atomic vibration frequency (M the mass of
// an atom):
//
//   tau_s = max(s0 - (s0 - s_inf) erf(kappa T^ ln(1 / r)), s0 r^beta)
//   tau_y = max(y0 - (y0 - y_inf) erf(kappa T^ ln(1 / r)),
//               min(y1 r^y2, s0 r^beta))
//   tau   = tau_s + (s0 - tau_y) / p ln(1 - (1 - exp(-b))
//                   exp(-p theta psi / ((s0 - tau_y) (exp(b) - 1)))),
//           b = p (tau_s - tau_y) / (s0 - tau_y)   (tau = tau_s where tau_y >= tau_s)
//   sigma_y = 2 G tau.
//
// p = 0 (the paper's tantalum) is the limit p -> 0 of tau: with
// d = tau_s - tau_y, b -> 0 as p d / (s0 - tau_y), exp(b) - 1 ~ b and
// 1 - exp(-b) ~ b, so the exponential tends to X0 = exp(-theta psi / d) and
// (s0 - tau_y) / p ln(1 - b X0) ~ (s0 - tau_y) / p (-b X0) = -d X0:
//
//   tau(p = 0) = tau_s - (tau_s - tau_y) exp(-theta psi / (tau_s - tau_y)),
//   d tau / d psi (p = 0) = theta exp(-theta psi / (tau_s - tau_y)),
//
// a Voce law from tau_y at psi = 0 with initial slope theta towards tau_s.
// For p > 0 the kernel evaluates the logarithm as log1p, so a small p
// joins this limit continuously.
//
// G and rho are the constant shear modulus and density of the fit (the
// paper lets G vary with rho and T). Additions of ours, as in the other
// laws: rates below eps_dot_0 count as eps_dot_0, and there is no strength at
// or above T_melt. With thermal softening off T is T_ref; with rate
// hardening off the rate is eps_dot_0.
#pragma once

#include <array>

#include "solver/material/model_switches.hpp"
#include "solver/material/strength_law.hpp"

namespace splat {

struct PrestonTonksWallaceParams {
  static constexpr const char* model = "preston-tonks-wallace";
  double theta = 0.0;      // initial hardening rate, normalised, -
  double p = 1.0;          // hardening shape, >= 0 (0: the limit above), -
  double s0 = 0.0;         // saturation stress at 0 K, normalised, -
  double s_inf = 0.0;      // saturation stress at high T^ ln(1/r), normalised, -
  double kappa = 0.0;      // temperature dependence of the thermally activated stresses, -
  double gamma = 1.0;      // rate scale of the thermally activated regime, -
  double y0 = 0.0;         // yield stress at 0 K, normalised, -
  double y_inf = 0.0;      // yield stress at high T^ ln(1/r), normalised, -
  double y1 = 0.0;         // yield stress factor of the overdriven-shock regime, -
  double y2 = 0.0;         // rate exponent of the overdriven-shock yield stress, -
  double beta = 0.0;       // rate exponent of the overdriven-shock saturation stress, -
  double G = 0.0;          // shear modulus the normalised stresses scale with, Pa
  double rho = 0.0;        // density of the atomic vibration frequency, kg/m^3
  double M = 0.0;          // molar mass, kg/mol
  double eps_dot_0 = 1.0;  // lowest rate counted, 1/s
  double T_ref = 300.0;    // reference (room) temperature, K
  double T_melt = 1000.0;  // melting temperature, K

  static constexpr std::array<LawField<PrestonTonksWallaceParams>, 17> fields() {
    using P = PrestonTonksWallaceParams;
    return {{{"theta", &P::theta, Quantity::dimensionless},
             {"p", &P::p, Quantity::dimensionless},
             {"s0", &P::s0, Quantity::dimensionless},
             {"s_inf", &P::s_inf, Quantity::dimensionless},
             {"kappa", &P::kappa, Quantity::dimensionless},
             {"gamma", &P::gamma, Quantity::dimensionless},
             {"y0", &P::y0, Quantity::dimensionless},
             {"y_inf", &P::y_inf, Quantity::dimensionless},
             {"y1", &P::y1, Quantity::dimensionless},
             {"y2", &P::y2, Quantity::dimensionless},
             {"beta", &P::beta, Quantity::dimensionless},
             {"G", &P::G, Quantity::shear_modulus},
             {"rho", &P::rho, Quantity::density},
             {"M", &P::M, Quantity::molar_mass},
             {"eps_dot_0", &P::eps_dot_0, Quantity::rate},
             {"T_ref", &P::T_ref, Quantity::room_temperature},
             {"T_melt", &P::T_melt, Quantity::melting_temperature}}};
  }
};

inline StrengthReferences strength_references(const PrestonTonksWallaceParams& ptw) {
  return {ptw.eps_dot_0, ptw.T_ref, ptw.T_melt};
}

// Flow stress and its partial derivatives at (eps_p, eps_dot_p, T): the
// strain slope in closed form (2 G theta e^-b X / (1 - (1 - e^-b) X), X the
// second exponential above), the rate slope by a central difference in ln
// rate (for the Newton steps of the return only). The constant G here has
// no pressure dependence.
FlowStress flow_stress(const PrestonTonksWallaceParams& ptw, const ModelSwitches& sw, double eps_p,
                       double eps_dot_p, double T, const PressureState& state);

}  // namespace splat
