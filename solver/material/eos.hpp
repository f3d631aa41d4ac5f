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

#include "solver/common/simd_lanes.hpp"
#include "solver/material/material.hpp"

namespace splat {

// Pressure without the energy term, and the Grueneisen coefficient that
// multiplies e (zero for the linear model): p = p_cold + gamma_e * e.
struct EosSplit {
  double p_cold;   // Pa
  double gamma_e;  // -
};

// p_cold of eos_split on the number type V (double or lanes); gamma_e, the
// same for every J, is set aside.
template <class V>
SPLAT_LANE_INLINE V eos_cold_pressure(const EosParams& eos, double K, double rho0, const V& J,
                                      double& gamma_e) {
  if (eos.model == EosModel::linear || !eos.mie_gruneisen) {
    gamma_e = 0.0;
    return -K * lane_log(J);
  }
  const MieGruneisenParams& mg = *eos.mie_gruneisen;
  gamma_e = mg.gamma0;
  const V mu = 1.0 / J - 1.0;
  const double rc2 = rho0 * mg.c0 * mg.c0;
  // The Hugoniot's denominator vanishes at mu = 1/(s-1) (a compression ratio
  // no impact below 3000 m/s reaches); keep it away from zero.
  const V denom = lane_max(1.0 - (mg.s - 1.0) * mu, V{} + 0.1);
  const V hugoniot = rc2 * mu * (1.0 + (1.0 - 0.5 * mg.gamma0) * mu) / (denom * denom);
  return mu <= 0.0 ? rc2 * mu : hugoniot;
}

inline EosSplit eos_split(const EosParams& eos, double K, double rho0, double J) {
  EosSplit split{0.0, 0.0};
  split.p_cold = eos_cold_pressure(eos, K, rho0, J, split.gamma_e);
  return split;
}

inline double apply_tension_damage(double p, double D) {
  return p < 0.0 ? (1.0 - D) * p : p;
}

}  // namespace splat
