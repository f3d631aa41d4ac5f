// Closed form of the Steinberg-Guinan flow stress (Steinberg, Cochran &
// Guinan 1980, J. Appl. Phys. 51, 1498), for the material-point verification
// tests, written from the published equation independently of the solver's
// kernel (no solver header is included here):
//   sigma_y = min(Y0 (1 + beta (eps_i + eps_p))^n, Y_max)
//             max(0, 1 + A P / eta^(1/3) - B (T - T_ref)),
// P the pressure (positive in compression), eta = rho / rho0; zero at or
// above T_melt; and its slope in plastic strain.
#pragma once

#include <algorithm>
#include <cmath>

namespace splat::exact {

struct SgCurve {
  double Y0, Y_max;  // Pa
  double beta, n;    // -
  double eps_i;      // -
  double A;          // 1/Pa
  double B;          // 1/K
  double T_ref;      // K
  double T_melt;     // K
};

// G(P, T) / G0, clamped at 0.
inline double sg_shear_ratio(const SgCurve& c, double T, double P, double eta) {
  return std::max(0.0, 1.0 + c.A * P / std::pow(eta, 1.0 / 3.0) - c.B * (T - c.T_ref));
}

// At pressure P (Pa) and compression eta (-); P = 0 and eta = 1 unless given.
inline double sg_flow_stress(const SgCurve& c, double eps_p, double /*rate*/, double T,
                             double P = 0.0, double eta = 1.0) {
  if (T >= c.T_melt) return 0.0;
  const double work = std::min(c.Y0 * std::pow(1.0 + c.beta * (c.eps_i + eps_p), c.n), c.Y_max);
  return work * sg_shear_ratio(c, T, P, eta);
}

inline double sg_hardening_slope(const SgCurve& c, double eps_p, double /*rate*/, double T,
                                 double P = 0.0, double eta = 1.0) {
  if (T >= c.T_melt) return 0.0;
  const double x = 1.0 + c.beta * (c.eps_i + eps_p);
  if (c.Y0 * std::pow(x, c.n) >= c.Y_max) return 0.0;
  return c.Y0 * c.n * c.beta * std::pow(x, c.n - 1.0) * sg_shear_ratio(c, T, P, eta);
}

}  // namespace splat::exact
