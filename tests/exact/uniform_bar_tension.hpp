// A uniform bar pulled in tension, quasi-static and adiabatic: the closed
// form the traction test (thesis 3.2, scenes/thesis/traction_cylinder_axisym.json)
// is checked against, written from the equations independently of the
// solver's kernels (only the Johnson-Cook curve of johnson_cook_closed_form.hpp).
//
// A bar of length L0 and section A0 stretched by u has the true strain
// eps = ln(1 + u / L0) everywhere (it stays uniform until it necks), split
// into the elastic strain sigma / E and the plastic strain eps_p. The
// section follows the elastic lateral strain -nu sigma / E and the volume-
// keeping plastic flow, A = A0 exp(-eps_p - 2 nu sigma / E):
//   elastic (E eps below the initial yield stress):
//            F = E eps A0 exp(-2 nu eps)           (E A0 eps to first order)
//   plastic: eps = eps_p + sigma / E with sigma = sigma_y(eps_p, eps_dot, T),
//            F = sigma A0 exp(-eps_p - 2 nu sigma / E)
//            (sigma A0 exp(-eps) when the elastic volume change is left
//            out, lower by (1 - 2 nu) sigma / E: 0.2 % for aluminium)
// with eps_dot = v / (L0 + u) at pull speed v, and the adiabatic temperature
// dT / d eps_p = chi sigma / (rho c_p) from T0 (chi the heat fraction).
// Inertia is left out (quasi-static).
#pragma once

#include <cmath>

#include "exact/johnson_cook_closed_form.hpp"

namespace splat::exact {

struct UniformBar {
  JcCurve law;                    // Johnson-Cook curve (its T_ref is the softening origin)
  double E = 0.0;                 // Young's modulus, Pa
  double nu = 0.0;                // Poisson's ratio, -
  double length = 0.0;            // L0, m
  double area = 0.0;              // A0, m^2
  double T0 = 0.0;                // initial temperature, K
  double heating = 0.0;           // chi / (rho c_p), K m^3 / J
  bool thermal_softening = true;  // false: sigma_y at T_ref
};

struct UniformBarState {
  double force = 0.0;  // N
  double eps_p = 0.0;  // -
  double T = 0.0;      // K
};

// The bar stretched by u (m) at pull speed v (m/s). The plastic branch
// marches eps_p in `steps` equal increments (trapezoidal rule for T) and
// interpolates the crossing of eps_p + sigma / E with eps.
inline UniformBarState uniform_bar_tension(const UniformBar& bar, double u, double v,
                                           int steps = 4000) {
  const double eps = std::log1p(u / bar.length);
  const double rate = v / (bar.length + u);
  const auto sigma = [&](double eps_p, double T) {
    return jc_flow_stress(bar.law, eps_p, rate, bar.thermal_softening ? T : bar.law.T_ref);
  };
  UniformBarState out;
  out.T = bar.T0;
  if (bar.E * eps <= sigma(0.0, bar.T0)) {
    out.force = bar.E * eps * bar.area * std::exp(-2.0 * bar.nu * eps);
    return out;
  }
  const double d = eps / steps;  // eps_p < eps
  double eps_p = 0.0, T = bar.T0, s = sigma(0.0, T);
  double excess = s / bar.E - eps;  // eps_p + sigma / E - eps, increasing in eps_p
  const auto force = [&](double eps_p_now, double sigma_now) {
    return sigma_now * bar.area * std::exp(-eps_p_now - 2.0 * bar.nu * sigma_now / bar.E);
  };
  for (int k = 0; k < steps; ++k) {
    const double T_pred = T + bar.heating * s * d;
    const double s_pred = sigma(eps_p + d, T_pred);
    const double T_next = T + bar.heating * 0.5 * (s + s_pred) * d;
    const double s_next = sigma(eps_p + d, T_next);
    const double excess_next = eps_p + d + s_next / bar.E - eps;
    if (excess_next >= 0.0) {
      const double w = -excess / (excess_next - excess);
      out.eps_p = eps_p + w * d;
      out.T = T + w * (T_next - T);
      out.force = force(out.eps_p, s + w * (s_next - s));
      return out;
    }
    eps_p += d;
    T = T_next;
    s = s_next;
    excess = excess_next;
  }
  out.eps_p = eps_p;
  out.T = T;
  out.force = force(eps_p, s);
  return out;
}

}  // namespace splat::exact
