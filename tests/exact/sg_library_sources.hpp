// Steinberg-Guinan sets of the library materials as their source prints them
// (Steinberg, UCRL-MA-106439 Change 1, 1996, as quoted in Uintah's
// SCGMaterials/*.xml), typed here independently of materials/*.json, so that
// the verification test (tests/verification/test_material_library.cpp)
// catches a slip in a library file's transcription or units. The library
// files derive E and nu from the set's G0 and bulk modulus rho0 c0^2; the
// test derives them again from the numbers here.
#pragma once

#include <array>

#include "exact/steinberg_guinan_closed_form.hpp"

namespace splat::exact {

struct SgSourceSet {
  const char* material;  // library name
  const char* source;    // where the numbers are printed
  SgCurve curve;         // Pa, Pa, -, -, -, 1/Pa, 1/K, K, K
  double G0;             // shear modulus at T_ref and zero pressure, Pa
  double density;        // rho0, kg/m^3
  double c0, s, gamma0;  // Mie-Grueneisen: m/s, -, -
  double c_p;            // J/(kg K)
};

// Steinberg's G0 and A are in the Uintah files in Pa and (mislabelled as
// 1/Pa) per Mbar: A here is the printed number times 1e-11 (1 Mbar = 1e11
// Pa). T_ref is the 300 K of Steinberg's form of G(T).
inline constexpr std::array<SgSourceSet, 3> sg_library_sources{{
    {"zn-sg",
     "Steinberg 1996, zinc",
     {0.15e9, 0.92e9, 100.0, 0.2, 0.0, 5.95 * 1e-11, 7.60e-4, 300.0, 900.0},
     39.5e9,
     7139.0,
     3030.0,
     1.55,
     2.24,
     389.0},
    {"ag-sg",
     "Steinberg 1996, silver",
     {0.05e9, 0.66e9, 28.0, 0.80, 0.0, 4.70 * 1e-11, 4.36e-4, 300.0, 1604.0},
     29.8e9,
     10490.0,
     3270.0,
     1.55,
     2.40,
     233.0},
    {"mg-az31b-sg",
     "Steinberg 1996, magnesium AZ31B-H24",
     {0.19e9, 0.48e9, 1100.0, 0.12, 0.0, 10.3 * 1e-11, 5.09e-4, 300.0, 1150.0},
     16.5e9,
     1780.0,
     4520.0,
     1.242,
     1.54,
     999.0},
}};

}  // namespace splat::exact
