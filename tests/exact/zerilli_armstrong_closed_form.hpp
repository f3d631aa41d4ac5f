// Closed forms of the Zerilli-Armstrong FCC flow stress (Zerilli & Armstrong
// 1987) for the material-point verification tests, written from the
// published equation independently of the solver's kernels (no solver header
// is included here): the flow stress and its slope in plastic strain (the
// adiabatic temperature is tests/support/flow_curve_checks.hpp's).
#pragma once

#include <algorithm>
#include <cmath>

namespace splat::exact {

struct ZaCurve {
  double C0, C2, C3, C4, eps_dot_0, T_melt;  // Pa, Pa, 1/K, 1/K, 1/s, K
};

// sigma = C0 + C2 eps_p^(1/2) exp(-C3 T + C4 T ln(rate / eps_dot_0)); rates
// below eps_dot_0 count as eps_dot_0, no strength at or above T_melt.
inline double za_flow_stress(const ZaCurve& c, double eps_p, double rate, double T) {
  if (T >= c.T_melt) return 0.0;
  const double ln_rate = std::log(std::max(rate / c.eps_dot_0, 1.0));
  return c.C0 + c.C2 * std::sqrt(std::max(eps_p, 0.0)) * std::exp(-c.C3 * T + c.C4 * T * ln_rate);
}

// d sigma / d eps_p at fixed rate and temperature.
inline double za_hardening_slope(const ZaCurve& c, double eps_p, double rate, double T) {
  if (eps_p <= 0.0 || T >= c.T_melt) return 0.0;
  const double ln_rate = std::log(std::max(rate / c.eps_dot_0, 1.0));
  return 0.5 * c.C2 / std::sqrt(eps_p) * std::exp(-c.C3 * T + c.C4 * T * ln_rate);
}

}  // namespace splat::exact
