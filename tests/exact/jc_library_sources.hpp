// Johnson-Cook sets of the library materials as their sources print them,
// typed here independently of materials/*.json, so that the verification
// test (tests/verification/test_material_library.cpp) catches a slip in a
// library file's transcription or units. Each entry names its source; the
// `source` field of the material file says where that source was read.
#pragma once

#include <array>

#include "exact/johnson_cook_closed_form.hpp"

namespace splat::exact {

struct JcSourceSet {
  const char* material;  // library name
  const char* source;    // where the numbers are printed
  JcCurve curve;         // Pa, Pa, -, -, 1/s, -, K, K
  double density;        // kg/m^3
  double E;              // Pa
  double nu;             // -
  double c_p;            // J/(kg K)
};

inline constexpr std::array<JcSourceSet, 3> jc_library_sources{{
    // Johnson & Cook (1983), OFHC copper; T_ref as the quoting record (294 K).
    {"cu-ofhc-jc",
     "Johnson & Cook 1983",
     {90e6, 292e6, 0.31, 0.025, 1.0, 1.09, 294.0, 1356.0},
     8960.0,
     124e9,
     0.34,
     383.0},
    // Lesuer, Kay & LeBlanc, UCRL-JC-134118 (2001), Table 1, 6061-T6; T_melt
    // and c_p at 294 K of Banerjee & Bhawalkar (2008).
    {"al6061-t6-jc",
     "Lesuer, Kay & LeBlanc 2001, Table 1",
     {324e6, 114e6, 0.42, 0.002, 1.0, 1.34, 294.0, 933.6},
     2703.0,
     68.9e9,
     0.33,
     893.0},
    // Abaqus deck jc_ti64_abq_builtin.inp (deg C converted to K).
    {"ti6al4v-jc",
     "Abaqus-VUMAT-Johnson-Cook validation deck",
     {1098e6, 1092e6, 0.93, 0.014, 1.0, 1.1, 293.15, 1905.15},
     4430.0,
     114.5e9,
     0.342,
     526.3},
}};

}  // namespace splat::exact
