// Preston-Tonks-Wallace sets of the library materials as their sources print
// them, typed here independently of materials/*.json, so that the
// verification test (tests/verification/test_material_library.cpp) catches a
// slip in a library file's transcription or units. The law here has a
// constant shear modulus; where the source gives G = G0 (1 - alpha T / T_melt)
// the set keeps G0 and alpha, and the test derives G at T_ref. The `source`
// field of the material file says where each number was read.
#pragma once

#include <array>

#include "exact/preston_tonks_wallace_closed_form.hpp"

namespace splat::exact {

struct PtwSourceSet {
  const char* material;  // library name
  const char* source;    // where the numbers are printed
  PtwCurve curve;        // with G = G0; see shear_modulus_at
  double alpha;          // temperature coefficient of G, -
  double T_ref;          // K
  double density;        // kg/m^3
  double E;              // Pa
  double nu;             // -
  double c_p;            // J/(kg K)
};

// G0 (1 - alpha T / T_melt), the source's shear modulus at temperature T (K).
inline double shear_modulus_at(const PtwSourceSet& s, double T) {
  return s.curve.G * (1.0 - s.alpha * T / s.curve.T_melt);
}

// The set with the constant shear modulus of the law here: G at T_ref.
inline PtwCurve curve_at_reference(const PtwSourceSet& s) {
  PtwCurve c = s.curve;
  c.G = shear_modulus_at(s, s.T_ref);
  return c;
}

inline constexpr std::array<PtwSourceSet, 2> ptw_library_sources{{
    // Preston, Tonks & Wallace (2003), tantalum (p = 0), as Uintah's
    // PTWPlasticTa.xml and F_UNCLE's Ptw.py print it: G0 722 kbar, alpha
    // 0.23, 16.75 g/cm^3, 180.948 g/mol, T_melt 2996 deg C; T_ref and
    // eps_dot_0 ours; density, E, nu and c_p of tantalum at periodictable.com.
    {"ta-ptw",
     "Preston, Tonks & Wallace 2003, tantalum",
     {0.02, 0.0, 0.012, 0.00325, 0.6, 4e-5, 0.01, 0.00125, 0.012, 0.4, 0.23, 72.2e9, 16750.0,
      0.180948, 1.0, 2996.0 + 273.15},
     0.23,
     300.0,
     16650.0,
     186e9,
     0.34,
     140.0},
    // Preston, Tonks & Wallace (2003), copper, as F_UNCLE's Ptw.py prints it
    // (the eleven strength parameters also in impala's OFHC copper test):
    // G0 518 kbar, alpha 0.20, 8.933 g/cm^3, T_melt 1084.88 deg C; molar mass
    // 63.546 g/mol (impala; F_UNCLE's 64.54 taken as a slip); T_ref and
    // eps_dot_0 ours; density, E, nu and c_p of cu-thesis (thesis Table 2.2).
    {"cu-ofhc-ptw",
     "Preston, Tonks & Wallace 2003, copper",
     {0.025, 2.0, 0.0085, 0.00055, 0.11, 1e-5, 0.0001, 0.0001, 0.094, 0.575, 0.25, 51.8e9, 8933.0,
      0.063546, 1.0, 1084.88 + 273.15},
     0.20,
     300.0,
     8960.0,
     124e9,
     0.34,
     385.0},
}};

}  // namespace splat::exact
