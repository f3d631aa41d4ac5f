#include "solver/material/zerilli_armstrong.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace splat {

FlowStress flow_stress(const ZerilliArmstrongParams& za, const ModelSwitches& sw, double eps_p,
                       double eps_dot_p, double T, const PressureState& /*state*/) {
  const double temp = sw.thermal_softening ? T : za.T_ref;
  if (temp >= za.T_melt) return {0.0, 0.0, 0.0};
  const bool rate_on = sw.rate_hardening && eps_dot_p > za.eps_dot_0;
  const double ln_rate = rate_on ? std::log(eps_dot_p / za.eps_dot_0) : 0.0;
  const double thermal = std::exp(-za.C3 * temp + za.C4 * temp * ln_rate);
  const double root = std::sqrt(std::max(eps_p, 0.0));
  const double hard = za.C2 * root * thermal;  // C2 eps_p^(1/2) exp(...)
  const double d_eps = root > 0.0  ? 0.5 * hard / eps_p
                       : za.C2 > 0 ? std::numeric_limits<double>::infinity()
                                   : 0.0;
  const double d_rate = rate_on ? hard * za.C4 * temp / eps_dot_p : 0.0;
  return {za.C0 + hard, d_eps, d_rate};
}

}  // namespace splat
