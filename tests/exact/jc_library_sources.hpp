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

inline constexpr std::array<JcSourceSet, 8> jc_library_sources{{
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
    // Johnson & Cook (1983), Nickel 200, as the Virtual-Twin-Cold-Spray
    // registry quotes it (T_ref 298 K, T_melt 1726 K); density, E, nu and c_p
    // from the same row.
    {"ni200-jc",
     "Johnson & Cook 1983, Nickel 200",
     {163e6, 648e6, 0.33, 0.006, 1.0, 1.44, 298.0, 1726.0},
     8890.0,
     207e9,
     0.31,
     444.0},
    // Karkalos & Markopoulos (2018), Table 2, 316L; density and c_p at 298 K
    // of Kim (ANL-75-55, 1975); E and nu from the registry row.
    {"ss316l-jc",
     "Karkalos & Markopoulos 2018, Table 2",
     {305e6, 1161e6, 0.61, 0.01, 1.0, 0.517, 298.0, 1673.0},
     7955.0,
     193e9,
     0.30,
     426.3},
    // Zha et al. (2020), Table 5 (after Chen et al.), Inconel 718; density and
    // c_p at 298 K of Agazhanov et al. (2019); E and nu from the registry row.
    {"in718-jc",
     "Zha et al. 2020, Table 5",
     {1241e6, 622e6, 0.6522, 0.0134, 1.0, 1.3, 298.0, 1609.0},
     8170.0,
     205e9,
     0.30,
     425.0},
    // Johnson & Cook (1983), Armco iron, as Zhang et al. (2017) quote it (m
    // 0.55; Uintah's copy has 1.44, see materials/fe-armco-jc.json; T_ref
    // 273 K); density, E, nu and c_p of pure iron at periodictable.com.
    {"fe-armco-jc",
     "Johnson & Cook 1983, Armco iron",
     {175e6, 380e6, 0.32, 0.06, 1.0, 0.55, 273.0, 1811.0},
     7874.0,
     211e9,
     0.29,
     449.0},
    // Pierazzo et al. (2008), Table 6, the set iSALE used for Al 1100-O, as
    // iSALE's example run prints it (T_ref 293 K, T_melt 933 K, nu 0.33, c_p
    // 896 J/(kg K)); density and E the handbook values of 1100-O.
    {"al1100-o-jc",
     "Pierazzo et al. 2008, Table 6 (iSALE, Al 1100-O)",
     {49e6, 157e6, 0.167, 0.016, 1.0, 1.7, 293.0, 933.0},
     2710.0,
     69e9,
     0.33,
     896.0},
}};

}  // namespace splat::exact
