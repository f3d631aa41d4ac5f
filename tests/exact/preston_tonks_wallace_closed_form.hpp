// Closed forms of the Preston-Tonks-Wallace flow stress (Preston, Tonks &
// Wallace 2003, J. Appl. Phys. 93, 211, eqs. for tau_s, tau_y and tau at
// constant rate and temperature) for the material-point verification tests,
// written from the published equations independently of the solver's
// kernels (no solver header is included here): the flow stress and its
// slope in plastic strain (the adiabatic temperature is
// tests/support/flow_curve_checks.hpp's).
#pragma once

#include <algorithm>
#include <cmath>

namespace splat::exact {

struct PtwCurve {
  double theta, p, s0, s_inf, kappa, gamma, y0, y_inf, y1, y2, beta;  // -
  double G, rho, M;                                                   // Pa, kg/m^3, kg/mol
  double eps_dot_0, T_melt;                                           // 1/s, K
};

// Normalised stresses at (rate, T): saturation tau_s and yield tau_y.
inline void ptw_bounds(const PtwCurve& c, double rate, double T, double& tau_s, double& tau_y) {
  const double n_atoms = c.rho * 6.02214076e23 / c.M;  // atoms per m^3
  const double pi = 3.14159265358979323846;
  const double xi_dot =
      0.5 * std::pow(4.0 * pi * n_atoms / 3.0, 1.0 / 3.0) * std::sqrt(c.G / c.rho);
  const double rate_ratio = std::max(rate, c.eps_dot_0) / (c.gamma * xi_dot);
  const double e =
      std::erf(c.kappa * (T / c.T_melt) * std::log(c.gamma * xi_dot / std::max(rate, c.eps_dot_0)));
  tau_s = std::max(c.s0 - (c.s0 - c.s_inf) * e, c.s0 * std::pow(rate_ratio, c.beta));
  tau_y = std::max(c.y0 - (c.y0 - c.y_inf) * e, std::min(c.y1 * std::pow(rate_ratio, c.y2),
                                                         c.s0 * std::pow(rate_ratio, c.beta)));
}

// p = 0 is the limit p -> 0 of the hardening law (the paper's tantalum):
// tau = tau_s - (tau_s - tau_y) exp(-theta eps_p / (tau_s - tau_y)).
inline double ptw_flow_stress(const PtwCurve& c, double eps_p, double rate, double T) {
  if (T >= c.T_melt) return 0.0;
  double ts = 0.0, ty = 0.0;
  ptw_bounds(c, rate, T, ts, ty);
  if (ts <= ty) return 2.0 * c.G * ts;
  if (c.p == 0.0)
    return 2.0 * c.G * (ts - (ts - ty) * std::exp(-c.theta * std::max(eps_p, 0.0) / (ts - ty)));
  const double b = c.p * (ts - ty) / (c.s0 - ty);
  const double decay =
      std::exp(-c.p * c.theta * std::max(eps_p, 0.0) / ((c.s0 - ty) * (std::exp(b) - 1.0)));
  const double tau = ts + (c.s0 - ty) / c.p * std::log(1.0 - (1.0 - std::exp(-b)) * decay);
  return 2.0 * c.G * tau;
}

// d sigma / d eps_p at fixed rate and temperature.
inline double ptw_hardening_slope(const PtwCurve& c, double eps_p, double rate, double T) {
  if (T >= c.T_melt) return 0.0;
  double ts = 0.0, ty = 0.0;
  ptw_bounds(c, rate, T, ts, ty);
  if (ts <= ty) return 0.0;
  if (c.p == 0.0)
    return 2.0 * c.G * c.theta * std::exp(-c.theta * std::max(eps_p, 0.0) / (ts - ty));
  const double b = c.p * (ts - ty) / (c.s0 - ty);
  const double decay =
      std::exp(-c.p * c.theta * std::max(eps_p, 0.0) / ((c.s0 - ty) * (std::exp(b) - 1.0)));
  return 2.0 * c.G * c.theta * std::exp(-b) * decay / (1.0 - (1.0 - std::exp(-b)) * decay);
}

}  // namespace splat::exact
