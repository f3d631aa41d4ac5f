// The stress update of n material points at once: update_point's arithmetic
// run on several points in SIMD lanes (GCC vector extensions; AVX-512, AVX2 or
// SSE2 chosen at run time), giving the same bits as update_point point by
// point. The loops over elements or particles gather the indices of the points
// of a block and call this instead of update_point one point at a time.
#pragma once

#include <cstddef>

#include "solver/material/point_update.hpp"

namespace splat {

// n points: state states[index[k]] advances as update_point(m, mc, sw,
// states[index[k]], d_eps[k], J_new[k], dt, length[k]) would; out[k] its
// result. The index[k] must be distinct (each state is read once, then
// written once). Lanes that need update_point's rare paths (no strength left,
// a return that has not converged within 12 vector iterations) are redone by
// update_point itself from the untouched state. Damage runs in lanes for
// Johnson-Cook initiation without initiation in the step and for the
// evolution of points initiated earlier; initiation inside the step and shear
// initiation (principal stresses) run per point in finish_plastic_step, the
// scalar code update_point itself uses.
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out);

}  // namespace splat
