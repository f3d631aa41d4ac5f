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

#include "solver/common/simd_math.hpp"
#include "solver/material/material.hpp"

// Vector values pass only between always_inline functions here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace splat {

// Pressure without the energy term, and the Grueneisen coefficient that
// multiplies e (zero for the linear model): p = p_cold + gamma_e * e.
// Written once for double and for SIMD lanes (V a vector of volume ratios):
// point_update_batch.cpp gives the same bits as the scalar update.
template <class V>
struct EosSplitT {
  V p_cold;   // Pa
  V gamma_e;  // -
};
using EosSplit = EosSplitT<double>;

template <class V>
[[gnu::always_inline]] inline EosSplitT<V> eos_split_t(const EosParams& eos, double K, double rho0,
                                                       V J) {
  if (eos.model == EosModel::linear || !eos.mie_gruneisen) {
    return {-K * simd::log(J), simd::broadcast<V>(0.0)};
  }
  const MieGruneisenParams& mg = *eos.mie_gruneisen;
  const V mu = 1.0 / J - 1.0;
  const double rc2 = rho0 * mg.c0 * mg.c0;
  // The Hugoniot's denominator vanishes at mu = 1/(s-1) (a compression ratio
  // no impact below 3000 m/s reaches); keep it away from zero.
  const V denom = simd::max<V>(1.0 - (mg.s - 1.0) * mu, simd::broadcast<V>(0.1));
  const V p_comp = rc2 * mu * (1.0 + (1.0 - 0.5 * mg.gamma0) * mu) / (denom * denom);
  return {simd::select<V>(mu <= 0.0, rc2 * mu, p_comp), simd::broadcast<V>(mg.gamma0)};
}

inline EosSplit eos_split(const EosParams& eos, double K, double rho0, double J) {
  return eos_split_t<double>(eos, K, rho0, J);
}

template <class V>
[[gnu::always_inline]] inline V apply_tension_damage_t(V p, V D) {
  return simd::select<V>(p < 0.0, (1.0 - D) * p, p);
}

inline double apply_tension_damage(double p, double D) {
  return apply_tension_damage_t<double>(p, D);
}

}  // namespace splat

#pragma GCC diagnostic pop
