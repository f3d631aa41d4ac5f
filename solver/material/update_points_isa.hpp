// update_points (point_update.hpp) as compiled for each instruction set
// (update_points_isa.cpp); point_update.cpp runs the one solver/common/isa.hpp
// chooses. Internal to solver/material.
#pragma once

#include <cstddef>

#include "solver/material/point_update.hpp"

namespace splat {

namespace isa_baseline {
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out);
}
namespace isa_v3 {
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out);
}
namespace isa_v4 {
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out);
}

}  // namespace splat
