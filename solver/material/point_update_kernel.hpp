// Pieces of update_point written once as templates on the number type V
// (double for one point, a GCC vector of doubles for SIMD lanes of points), so
// that update_point (point_update.cpp) and update_points
// (point_update_batch.cpp) do the same IEEE operations in the same order and
// give the same bits. Tensors are the 9 entries of a column-major Mat3
// (Mat3::data()); sums run over them in storage order.
#pragma once

#include "solver/common/simd_math.hpp"
#include "solver/material/point_update.hpp"

// Vector values pass only between always_inline functions here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace splat::point_kernel {

// sum_i a_i b_i over the 9 entries, in storage order.
template <class V>
[[gnu::always_inline]] inline V sum_products9(const V* a, const V* b) {
  V sum = a[0] * b[0];
  for (int i = 1; i < 9; ++i) sum = sum + a[i] * b[i];
  return sum;
}

// Elastic predictor s + 2 G_d dev(d_eps).
template <class V>
[[gnu::always_inline]] inline void elastic_predictor(const V* s_old, const V* d_eps, V two_g,
                                                     V* s) {
  const V third = ((d_eps[0] + d_eps[4]) + d_eps[8]) / 3.0;
  for (int i = 0; i < 9; ++i) {
    const bool diagonal = i % 4 == 0;
    s[i] = s_old[i] + two_g * (diagonal ? d_eps[i] - third : d_eps[i]);
  }
}

// von Mises stress sqrt(3/2 s:s) of a deviator.
template <class V>
[[gnu::always_inline]] inline V von_mises9(const V* s) {
  return simd::sqrt(1.5 * sum_products9(s, s));
}

// (s - p I) : d_eps.
template <class V>
[[gnu::always_inline]] inline V stress_power9(const V* s, V p, const V* d_eps) {
  V sum = (s[0] - p) * d_eps[0];
  for (int i = 1; i < 9; ++i) sum = sum + (i % 4 == 0 ? s[i] - p : s[i]) * d_eps[i];
  return sum;
}

// What update_point does after the radial return and the EOS when the step was
// plastic (dp > 0) and damage is on: damage, then the strength of the end
// state and the peaks. st holds the end-of-step s, p, e, eps_p, T and
// sigma_y = scale * hard_rate of the increment; `heated` says whether T moved.
void finish_plastic_step(const Material& m, const ModelSwitches& sw, PointState& st, double dp,
                         double dt, double length, double scale, double rate_f, bool heated);

}  // namespace splat::point_kernel

#pragma GCC diagnostic pop
