// Closed forms of linear elastic wave propagation (any elasticity text, e.g.
// Graff, Wave Motion in Elastic Solids, ch. 1 and 5), independent of the
// solver's headers.
#pragma once

#include <cmath>

namespace splat::exact {

// Longitudinal (P-wave, uniaxial-strain) speed sqrt((K + 4G/3) / rho)
//   = sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu) rho)), m/s.
inline double longitudinal_wave_speed(double E, double nu, double rho) {
  return std::sqrt(E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * rho));
}

// Bar (uniaxial-stress, long-wavelength) speed sqrt(E / rho), m/s.
inline double bar_wave_speed(double E, double rho) {
  return std::sqrt(E / rho);
}

// Stress behind a plane wave front driven by a particle velocity step v
// (momentum balance across the front): sigma = -rho c v, Pa (compressive for
// v along the propagation direction).
inline double wave_front_stress(double rho, double c, double v) {
  return -rho * c * v;
}

}  // namespace splat::exact
