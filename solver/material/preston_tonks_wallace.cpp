#include "solver/material/preston_tonks_wallace.hpp"

#include <algorithm>
#include <cmath>

namespace splat {

namespace {

constexpr double avogadro = 6.02214076e23;  // 1/mol
constexpr double pi = 3.14159265358979323846;

// The normalised flow stress tau and d tau / d psi (header equations).
struct NormalisedStress {
  double value;  // -
  double d_psi;  // -
};

NormalisedStress normalised_stress(const PrestonTonksWallaceParams& w, double psi, double rate,
                                   double T_hat) {
  const double atom_mass = w.M / avogadro;  // kg
  const double xi_dot =
      0.5 * std::cbrt(4.0 * pi * w.rho / (3.0 * atom_mass)) * std::sqrt(w.G / w.rho);  // 1/s
  const double r = rate / (w.gamma * xi_dot);
  const double activated = std::erf(w.kappa * T_hat * std::log(1.0 / r));
  const double shock_saturation = w.s0 * std::pow(r, w.beta);
  const double tau_s = std::max(w.s0 - (w.s0 - w.s_inf) * activated, shock_saturation);
  const double tau_y = std::max(w.y0 - (w.y0 - w.y_inf) * activated,
                                std::min(w.y1 * std::pow(r, w.y2), shock_saturation));
  const double a = w.s0 - tau_y;
  if (!(tau_s > tau_y) || a == 0.0) return {tau_s, 0.0};
  const double d = tau_s - tau_y;
  if (w.p == 0.0) {
    // The p -> 0 limit (header): a Voce law.
    const double X0 = std::exp(-w.theta * psi / d);
    return {tau_s - d * X0, w.theta * X0};
  }
  const double b = w.p * d / a;
  const double X = std::exp(-w.p * w.theta * psi / (a * std::expm1(b)));
  const double c = -std::expm1(-b);  // 1 - exp(-b)
  const double inner = 1.0 - c * X;
  return {tau_s + a / w.p * std::log1p(-c * X), w.theta * (1.0 - c) * X / inner};
}

}  // namespace

FlowStress flow_stress(const PrestonTonksWallaceParams& w, const ModelSwitches& sw, double eps_p,
                       double eps_dot_p, double T, const PressureState& /*state*/) {
  const double temp = sw.thermal_softening ? T : w.T_ref;
  if (temp >= w.T_melt) return {0.0, 0.0, 0.0};
  const bool rate_on = sw.rate_hardening && eps_dot_p > w.eps_dot_0;
  const double rate = rate_on ? eps_dot_p : w.eps_dot_0;
  const double T_hat = temp / w.T_melt;
  const double psi = std::max(eps_p, 0.0);
  const NormalisedStress tau = normalised_stress(w, psi, rate, T_hat);
  double d_rate = 0.0;
  if (rate_on) {
    constexpr double h = 1e-4;  // step in ln rate
    const double up = normalised_stress(w, psi, rate * std::exp(h), T_hat).value;
    const double down = normalised_stress(w, psi, rate * std::exp(-h), T_hat).value;
    d_rate = 2.0 * w.G * (up - down) / (2.0 * h * rate);
  }
  return {2.0 * w.G * tau.value, 2.0 * w.G * tau.d_psi, d_rate};
}

}  // namespace splat
