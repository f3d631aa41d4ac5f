// Artificial bulk viscosity and the element's stable time step (LS-DYNA
// *CONTROL_BULK_VISCOSITY; von Neumann-Richtmyer quadratic plus Landshoff
// linear term), acting in compression only:
//   q  = rho L_c (Q2 L_c tr(D)^2 - Q1 c tr(D))   for tr(D) < 0, else 0,
//   dt = L_c / (Qv + sqrt(Qv^2 + c^2)),
//   Qv = Q1 c + Q2 L_c |tr(D)|                   for tr(D) < 0, else 0,
// with rho the current density, L_c the element's characteristic length, D
// the rate of deformation and c the P-wave speed. q adds to the pressure in
// the element's internal forces (sigma - q I), never to the material state.
//
// c is the undamaged P-wave speed sqrt((K + 4G/3) / rho0)
// (MaterialConstants::wave_speed). Damage lowers the kernel's shear modulus
// and tensile pressure by (1 - D), which only slows the waves, and the
// compressive bulk response is not degraded, so the undamaged speed is a
// conservative (never too long) time-step bound and costs nothing to evaluate.
#pragma once

#include <cmath>

namespace splat {

struct BulkViscosityCoefficients {
  double Q1 = 0.06;  // linear, -
  double Q2 = 1.5;   // quadratic, -
};

// q, Pa (>= 0).
inline double bulk_viscosity_pressure(const BulkViscosityCoefficients& k, double rho, double L_c,
                                      double c, double tr_D) {
  if (tr_D >= 0.0) return 0.0;
  return rho * L_c * (k.Q2 * L_c * tr_D * tr_D - k.Q1 * c * tr_D);
}

// Qv, m/s (>= 0).
inline double bulk_viscosity_speed(const BulkViscosityCoefficients& k, double L_c, double c,
                                   double tr_D) {
  if (tr_D >= 0.0) return 0.0;
  return k.Q1 * c - k.Q2 * L_c * tr_D;
}

// dt = L_c / (Qv + sqrt(Qv^2 + c^2)), s.
inline double stable_time_step(double L_c, double c, double Qv) {
  return L_c / (Qv + std::sqrt(Qv * Qv + c * c));
}

}  // namespace splat
