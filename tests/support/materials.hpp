// Materials the element tests and benchmarks build by hand (no material file
// needed): Johnson-Cook OFHC copper, and the switches that leave damage out.
#pragma once

#include "solver/material/material.hpp"

namespace splat::test_support {

// Johnson-Cook copper (A 90 MPa, B 292 MPa, n 0.31, C 0.025, m 1.09,
// T_ref 300 K, T_melt 1356 K), density 8960 kg/m^3, E 124 GPa, nu 0.34,
// c_p 385 J/(kg K); no damage parameters.
inline Material jc_copper() {
  Material m;
  m.name = "copper";
  m.density = 8960.0;
  m.elastic = {124e9, 0.34};
  m.strength.A = 90e6, m.strength.B = 292e6, m.strength.n = 0.31, m.strength.C = 0.025;
  m.strength.m = 1.09, m.strength.T_ref = 300.0, m.strength.T_melt = 1356.0;
  m.thermal.c_p = 385.0;
  return m;
}

inline ModelSwitches no_damage() {
  ModelSwitches sw;
  sw.damage = false;
  return sw;
}

}  // namespace splat::test_support
