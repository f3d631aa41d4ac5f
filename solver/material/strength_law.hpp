// What every strength law (johnson_cook.hpp, zerilli_armstrong.hpp, ...)
// offers the rest of the code besides its flow stress: its parameters listed
// by name, unit and kind of quantity (for reading, writing and the magnitude
// guard of solver/input/material_io.cpp), and the reference rate and
// temperatures that damage laws and scene defaults take from it.
#pragma once

namespace splat {

// Kind of a law parameter: decides the range a metal's value must lie in
// (solver/input/material_io.cpp) and the unit it is written in.
enum class Quantity {
  yield_stress,         // a stress every metal has: 1 MPa .. 10 GPa, Pa
  hardening_stress,     // a stress that may be 0, else 1 MPa .. 10 GPa, Pa
  dimensionless,        // -
  rate,                 // 1/s
  room_temperature,     // 1 .. 1000 K
  melting_temperature,  // 300 .. 4500 K
  inverse_temperature,  // 1/K
  shear_modulus,        // a metal's: 1 GPa .. 1000 GPa, Pa
  density,              // a metal's: 500 .. 25000 kg/m^3
  molar_mass,           // a metal's: 0.006 .. 0.3 kg/mol
};

// One parameter of the law with parameter struct P.
template <class P>
struct LawField {
  const char* name;   // JSON member under "strength"
  double P::*member;  // where it lives in P
  Quantity quantity;
};

// The reference plastic rate and temperatures a law is stated at: the
// initial temperature of a body by default and the rate and homologous
// temperature of the Johnson-Cook failure strain (damage.hpp).
struct StrengthReferences {
  double eps_dot_0 = 1.0;  // reference plastic strain rate, 1/s
  double T_ref = 300.0;    // reference (room) temperature, K
  double T_melt = 1000.0;  // melting temperature, K
};

// Flow stress of a law at (eps_p, eps_dot_p, T) and its partial derivatives.
struct FlowStress {
  double value;    // sigma_y, Pa
  double d_eps_p;  // d sigma_y / d eps_p, Pa
  double d_rate;   // d sigma_y / d eps_dot_p, Pa s
};

}  // namespace splat
