// A prescribed velocity given as a table of (time, velocity) points: what a
// boundary condition of type velocity with a `history` asks for
// (schemas/scene.schema.json, #/definitions/boundary_condition). Pure
// functions of the table and the time; the time loop
// (solver/core/simulation.cpp, stage 1) asks for the mean over each step.
//
// Between two points t_k < t_{k+1}, with xi = (t - t_k) / (t_{k+1} - t_k):
//   linear:       v(t) = v_k + (v_{k+1} - v_k) xi
//   smooth-step:  v(t) = v_k + (v_{k+1} - v_k) xi^3 (10 - 15 xi + 6 xi^2)
// (the smooth step of Abaqus's *AMPLITUDE, DEFINITION=SMOOTH STEP: zero first
// and second derivatives at every point, so a ramp from rest starts and ends
// without a jump in acceleration). Before the first point the first velocity
// holds, after the last point the last one.
//
// The displacement D(t) = integral of v from 0 to t is exact for either
// form (the smooth step integrates to xi^4 (5/2 - 3 xi + xi^2)), so a node
// moved by D(t + dt) - D(t) in each step is where the table puts it, whatever
// the step.
#pragma once

#include <vector>

#include "solver/common/types.hpp"

namespace splat {

enum class HistoryInterpolation { linear, smooth_step };

struct VelocityHistory {
  std::vector<double> time;    // s, >= 0, strictly increasing, at least two points
  std::vector<Vec3> velocity;  // m/s, one per time
  HistoryInterpolation interpolation = HistoryInterpolation::linear;
};

// v(t), m/s.
Vec3 history_velocity(const VelocityHistory& h, double t);

// D(t) = integral of v from 0 to t, m (t >= 0).
Vec3 history_displacement(const VelocityHistory& h, double t);

// The mean velocity over [t, t + dt], (D(t + dt) - D(t)) / dt, m/s; v(t)
// when dt is 0.
Vec3 history_mean_velocity(const VelocityHistory& h, double t, double dt);

}  // namespace splat
