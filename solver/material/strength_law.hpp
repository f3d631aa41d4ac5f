// What every strength law (johnson_cook.hpp, zerilli_armstrong.hpp, ...)
// offers the rest of the code besides its flow stress: its parameters listed
// by name, unit and kind of quantity (for reading, writing and the magnitude
// guard of solver/input/material_io.cpp), and the reference rate and
// temperatures that damage laws and scene defaults take from it; and what
// every law is given besides eps_p, eps_dot_p and T (PressureState).
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
  inverse_pressure,     // 0 or a metal's dG/dP / G0: 1e-12 .. 1e-9 1/Pa (0.1 .. 100 /Mbar)
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

// The pressure and compression of the point, for a law whose flow stress
// depends on them (Steinberg-Guinan's G(P, T)); the others ignore it. The
// default is the reference state: no pressure, rho = rho0.
struct PressureState {
  double P = 0.0;    // pressure, positive in compression, Pa
  double eta = 1.0;  // compression rho / rho0 = V0 / V = 1 / J, -
};

// A law whose flow stress depends on the PressureState declares
//   static constexpr bool pressure_dependent = true;
// in its parameter struct: the pressure moves in elastic steps too, so the
// point update then refreshes the point's strength caches every step.
template <class Law>
constexpr bool pressure_dependent() {
  if constexpr (requires { Law::pressure_dependent; }) {
    return Law::pressure_dependent;
  } else {
    return false;
  }
}

// Flow stress of a law at (eps_p, eps_dot_p, T) and its partial derivatives.
struct FlowStress {
  double value;    // sigma_y, Pa
  double d_eps_p;  // d sigma_y / d eps_p, Pa
  double d_rate;   // d sigma_y / d eps_dot_p, Pa s
};

}  // namespace splat
