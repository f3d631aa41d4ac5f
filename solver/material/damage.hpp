// Damage: initiation indicator and evolution (thesis 2.1.4.2).
//
// Initiation: omega = sum d_eps_p / eps_f(state); damage starts when omega
// reaches 1, at the plastic strain eps_D.
//  - Johnson-Cook ductile (eq. 2.6, sign convention of Johnson & Cook 1985):
//      eps_f = (D1 + D2 exp(D3 eta)) (1 + D4 ln max(eps_dot*, 1)) (1 + D5 T*),
//    eta = sigma_mean / sigma_eq the stress triaxiality. The thesis prints the
//    temperature term as (T*)^m; the 1985 law is linear in T*, used here.
//  - Shear failure (eq. 2.3-2.5): theta = (k_s p + q) / tau_max clamped to
//    [theta_min, theta_max], tau_max = (sigma_1 - sigma_3) / 2 the largest
//    shear stress (the thesis takes the largest off-diagonal component, which
//    depends on the axes; the principal form is frame independent). The cubic
//    eps_S = A theta^3 + B theta^2 + C theta + D at the low and high rates is
//    interpolated linearly in the plastic strain rate and clamped outside.
// Both failure strains are kept >= min_failure_strain so that D1 < 0 (Ti6Al4V)
// at high triaxiality cannot give a negative or zero failure strain.
//
// Evolution once initiated (plastic strain past eps_D only), capped at D_max:
//  - instant:          D = D_max
//  - plastic-strain (eq. 2.7):  dD = d_eps_p / (eps_p_max - eps_D)
//  - fracture-energy (eq. 2.8): dD = D_max sigma_y d_eps_p L / G_f, with L the
//    characteristic length of the element (m); eq. 2.8 divides a work per unit
//    volume by G_f in J/m^2, so a length is needed for the units to close
//    (as in Abaqus's displacement-based softening).
#pragma once

#include <algorithm>
#include <cmath>

#include "solver/common/types.hpp"
#include "solver/material/material.hpp"

namespace splat {

inline constexpr double min_failure_strain = 1e-6;  // -

// Largest shear stress (sigma_1 - sigma_3) / 2 of a symmetric stress, Pa.
double max_shear_stress(const Mat3& sigma);

// The reference rate and homologous temperature T* = (T - T_ref) / (T_melt -
// T_ref) are those of the material's strength law (`ref`).
inline double jc_failure_strain(const JohnsonCookFailureParams& d, const StrengthReferences& ref,
                                bool rate_term, bool thermal_term, double triaxiality,
                                double eps_dot_p, double T) {
  double eps_f = d.D1 + d.D2 * std::exp(d.D3 * triaxiality);
  if (rate_term && eps_dot_p > ref.eps_dot_0)
    eps_f *= 1.0 + d.D4 * std::log(eps_dot_p / ref.eps_dot_0);
  if (thermal_term) {
    const double t_star = std::clamp((T - ref.T_ref) / (ref.T_melt - ref.T_ref), 0.0, 1.0);
    eps_f *= 1.0 + d.D5 * t_star;
  }
  return std::max(eps_f, min_failure_strain);
}

inline double shear_failure_strain(const ShearFailureParams& sf, double theta, double eps_dot_p) {
  const double t = std::clamp(theta, sf.theta_min, sf.theta_max);
  auto cubic = [t](const double(&c)[4]) { return ((c[0] * t + c[1]) * t + c[2]) * t + c[3]; };
  const double lo = cubic(sf.low);
  const double hi = cubic(sf.high);
  const double w = std::clamp((eps_dot_p - sf.rate_low) / (sf.rate_high - sf.rate_low), 0.0, 1.0);
  return std::max(lo + (hi - lo) * w, min_failure_strain);
}

// Shear stress ratio of eq. 2.3 with p positive in compression, q the von
// Mises stress and tau_max the largest shear stress.
inline double shear_stress_ratio(double k_s, double p, double q, double tau_max) {
  return tau_max > 0.0 ? (k_s * p + q) / tau_max : 0.0;
}

// Reproducible random initial damage in [0, max): a hash of (seed, index) so
// the value of a point does not depend on thread count or visiting order.
inline double initial_random_damage(unsigned long long seed, unsigned long long index,
                                    double max_damage) {
  unsigned long long z = seed * 0x9E3779B97F4A7C15ULL + index + 0x632BE59BD9B4E019ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;  // splitmix64 finaliser
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return max_damage * static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace splat
