// Materials the element tests and benchmarks build by hand (no material file
// needed): Johnson-Cook OFHC copper, the switches that leave damage out, and
// linear-elastic steel as a scene's inline material.
#pragma once

#include <nlohmann/json.hpp>

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
  m.strength = JohnsonCookParams{
      .A = 90e6, .B = 292e6, .n = 0.31, .C = 0.025, .m = 1.09, .T_ref = 300.0, .T_melt = 1356.0};
  m.thermal.c_p = 385.0;
  return m;
}

inline ModelSwitches no_damage() {
  ModelSwitches sw;
  sw.damage = false;
  return sw;
}

// Linear-elastic steel for scenes (round numbers): E 200 GPa, nu 0.3,
// rho 7850 kg/m^3, and a Johnson-Cook yield stress of 10 GPa (the largest a
// material document may give) that no test reaches.
inline constexpr double steel_E = 200e9;     // Pa
inline constexpr double steel_nu = 0.3;      // -
inline constexpr double steel_rho = 7850.0;  // kg/m^3
inline nlohmann::json elastic_steel_json() {
  return {{"name", "elastic-steel"},
          {"source", "round numbers for steel; yield stress raised out of reach"},
          {"density", steel_rho},
          {"elastic", {{"E", steel_E}, {"nu", steel_nu}}},
          {"strength",
           {{"model", "johnson-cook"},
            {"A", 1e10},
            {"B", 0.0},
            {"n", 1.0},
            {"C", 0.0},
            {"eps_dot_0", 1.0},
            {"m", 1.0},
            {"T_ref", 300.0},
            {"T_melt", 1800.0}}},
          {"thermal", {{"c_p", 460.0}, {"heat_fraction", 0.9}}},
          {"eos", {{"model", "linear"}}}};
}

}  // namespace splat::test_support
