// Equations of state: pressure p (positive in compression) from the volume
// ratio J = V / V0 and the internal energy per unit reference volume e.
//
// linear:        p = -K ln J                     (Hencky volumetric response;
//                                                 p = K (1 - J) for small strain)
// Mie-Grueneisen (linear Us-up Hugoniot, as in LS-DYNA's *EOS_GRUNEISEN with
// a = 0), mu = 1/J - 1:
//   mu > 0:  p = rho0 c0^2 mu (1 + (1 - Gamma0/2) mu) / (1 - (s - 1) mu)^2 + Gamma0 e
//   mu <= 0: p = rho0 c0^2 mu + Gamma0 e
// Damage: cracks carry no tension, so a negative pressure is scaled by (1 - D);
// compression is not degraded.
#pragma once

#include <algorithm>
#include <cmath>

#include "solver/material/material.hpp"

namespace splat {

// Pressure without the energy term, and the Grueneisen coefficient that
// multiplies e (zero for the linear model): p = p_cold + gamma_e * e.
struct EosSplit {
  double p_cold;   // Pa
  double gamma_e;  // -
};

inline EosSplit eos_split(const EosParams& eos, double K, double rho0, double J) {
  if (eos.model == EosModel::linear || !eos.mie_gruneisen) {
    return {-K * std::log(J), 0.0};
  }
  const MieGruneisenParams& mg = *eos.mie_gruneisen;
  const double mu = 1.0 / J - 1.0;
  const double rc2 = rho0 * mg.c0 * mg.c0;
  if (mu <= 0.0) {
    return {rc2 * mu, mg.gamma0};
  }
  // The Hugoniot's denominator vanishes at mu = 1/(s-1) (a compression ratio
  // no impact below 3000 m/s reaches); keep it away from zero.
  const double denom = std::max(1.0 - (mg.s - 1.0) * mu, 0.1);
  return {rc2 * mu * (1.0 + (1.0 - 0.5 * mg.gamma0) * mu) / (denom * denom), mg.gamma0};
}

inline double apply_tension_damage(double p, double D) {
  return p < 0.0 ? (1.0 - D) * p : p;
}

}  // namespace splat
