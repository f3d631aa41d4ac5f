// Material-point driver: one point driven through a constant-rate homogeneous
// deformation, the single-element test engineers use to calibrate and check
// strength-law and damage parameters before simulating a body.
//
//  uniaxial-stress: axial stretch at constant true strain rate; the lateral
//                   strain rates are iterated each step until the lateral
//                   stress is zero.
//  uniaxial-strain: axial stretch at constant true strain rate, no lateral
//                   motion (the state behind a planar shock).
//  simple-shear:    x-velocity grows with y, engineering shear strain
//                   gamma = rate * t; the Jaumann rotation acts.
//
// Reported strain is the true (logarithmic) axial strain, or gamma in simple
// shear; stress is the axial Cauchy stress, or the shear stress sigma_xy.
#pragma once

#include <string>
#include <vector>

#include "solver/material/material.hpp"

namespace splat {

enum class LoadingMode { uniaxial_stress, uniaxial_strain, simple_shear };

LoadingMode parse_loading_mode(const std::string& text);  // throws std::invalid_argument

struct MaterialPointRequest {
  Material material;
  ModelSwitches switches;
  LoadingMode mode = LoadingMode::uniaxial_stress;
  double strain_rate = 1.0;     // magnitude of the prescribed rate, 1/s (> 0)
  double max_strain = 0.1;      // final strain, signed: negative is compression, -
  int steps = 1000;             // number of equal time steps (>= 1)
  double temperature = 300.0;   // initial temperature, K
  double length = 1e-3;         // characteristic length for the fracture-energy law, m
  double initial_damage = 0.0;  // initial damage, -
};

struct MaterialPointRow {
  double time = 0.0;              // s
  double strain = 0.0;            // -
  double stress = 0.0;            // Pa
  double plastic_strain = 0.0;    // -
  double temperature = 0.0;       // K
  double damage = 0.0;            // -
  double yield_stress = 0.0;      // Pa
  double pressure = 0.0;          // Pa
  double triaxiality = 0.0;       // -
  double damage_indicator = 0.0;  // -
  int iterations = 0;             // return-mapping iterations of the step
};

struct MaterialPointResult {
  std::vector<MaterialPointRow> rows;  // initial state first, then one per step
  bool converged = true;               // false if any solve failed
  std::string message;                 // why not converged
};

// Validates the request (throws std::invalid_argument naming the bad field)
// and runs it.
MaterialPointResult run_material_point(const MaterialPointRequest& request);

// CSV with header
// time,strain,stress,plastic_strain,temperature,damage,yield_stress,pressure,
// triaxiality,damage_indicator,iterations (SI units).
std::string material_point_csv(const MaterialPointResult& result);

}  // namespace splat
