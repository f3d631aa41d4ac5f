// Closed forms for the material-point verification tests, written from the
// published equations independently of the solver's kernels (no solver
// header is included here).
#pragma once

#include <algorithm>
#include <cmath>

namespace splat::exact {

struct JcCurve {
  double A, B, n, C, eps_dot_0, m, T_ref, T_melt;  // Pa, Pa, -, -, 1/s, -, K, K
};

// Thesis eq. 1.26 with the usual clamps (no gain below the reference rate or
// temperature, zero strength at melt).
inline double jc_flow_stress(const JcCurve& c, double eps_p, double rate, double T) {
  const double hardening = c.A + c.B * std::pow(std::max(eps_p, 0.0), c.n);
  const double rate_term = 1.0 + c.C * std::log(std::max(rate / c.eps_dot_0, 1.0));
  const double t_star = std::clamp((T - c.T_ref) / (c.T_melt - c.T_ref), 0.0, 1.0);
  return hardening * rate_term * (1.0 - std::pow(t_star, c.m));
}

// d sigma / d eps_p of eq. 1.26 at fixed rate and temperature.
inline double jc_hardening_slope(const JcCurve& c, double eps_p, double rate, double T) {
  if (eps_p <= 0.0) return 0.0;
  const double rate_term = 1.0 + c.C * std::log(std::max(rate / c.eps_dot_0, 1.0));
  const double t_star = std::clamp((T - c.T_ref) / (c.T_melt - c.T_ref), 0.0, 1.0);
  return c.B * c.n * std::pow(eps_p, c.n - 1.0) * rate_term * (1.0 - std::pow(t_star, c.m));
}

// Johnson & Cook (1985) failure strain.
inline double jc_failure_strain(double D1, double D2, double D3, double D4, double D5,
                                double triaxiality, double rate_ratio, double t_star) {
  return (D1 + D2 * std::exp(D3 * triaxiality)) * (1.0 + D4 * std::log(std::max(rate_ratio, 1.0))) *
         (1.0 + D5 * t_star);
}

// Damage of eq. 2.7 after initiation at eps_d, growing linearly to 1 at
// eps_max and capped at D_max.
inline double linear_damage(double eps_p, double eps_d, double eps_max, double D_max) {
  if (eps_p <= eps_d) return 0.0;
  return std::min((eps_p - eps_d) / (eps_max - eps_d), D_max);
}

// Elastic uniaxial strain: axial stress = (K + 4G/3) * strain.
inline double uniaxial_strain_stress(double E, double nu, double strain) {
  const double K = E / (3.0 * (1.0 - 2.0 * nu));
  const double G = E / (2.0 * (1.0 + nu));
  return (K + 4.0 * G / 3.0) * strain;
}

}  // namespace splat::exact
