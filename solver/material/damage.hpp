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

#include "solver/common/simd_math.hpp"
#include "solver/material/material.hpp"

// Vector values pass only between always_inline functions here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace splat {

inline constexpr double min_failure_strain = 1e-6;  // -

// Written once for double and for SIMD lanes (V a vector of states):
// point_update_batch.cpp gives the same bits as the scalar update.
template <class V>
[[gnu::always_inline]] inline V jc_failure_strain_t(const JohnsonCookFailureParams& d,
                                                    const JohnsonCookParams& jc, bool rate_term,
                                                    bool thermal_term, V triaxiality, V eps_dot_p,
                                                    V T) {
  V eps_f = d.D1 + d.D2 * simd::exp(d.D3 * triaxiality);
  if (rate_term) {
    const V rate = 1.0 + d.D4 * simd::log(eps_dot_p / jc.eps_dot_0);
    eps_f = simd::select<V>(eps_dot_p > jc.eps_dot_0, eps_f * rate, eps_f);
  }
  if (thermal_term) {
    // std::clamp(t, 0, 1): t < 0 ? 0 : (1 < t ? 1 : t)
    const V t = (T - jc.T_ref) / (jc.T_melt - jc.T_ref);
    const V t_star = simd::select<V>(t < 0.0, simd::broadcast<V>(0.0),
                                     simd::select<V>(1.0 < t, simd::broadcast<V>(1.0), t));
    eps_f = eps_f * (1.0 + d.D5 * t_star);
  }
  return simd::max<V>(eps_f, simd::broadcast<V>(min_failure_strain));
}

inline double jc_failure_strain(const JohnsonCookFailureParams& d, const JohnsonCookParams& jc,
                                bool rate_term, bool thermal_term, double triaxiality,
                                double eps_dot_p, double T) {
  return jc_failure_strain_t<double>(d, jc, rate_term, thermal_term, triaxiality, eps_dot_p, T);
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

#pragma GCC diagnostic pop
