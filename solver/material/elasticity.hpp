// Isotropic hypo-elasticity with the Jaumann objective stress rate.
//
// Deviatoric Cauchy stress, integrated in a frame that co-rotates with the
// material spin W = skew(grad v):
//   s_{n+1} = Q s_n Q^T + 2 G (1 - D) dev(d_eps),
//   Q = (I - W dt / 2)^{-1} (I + W dt / 2)        (Hughes & Winget 1980),
// which is the Jaumann rate ds/dt - W s + s W = 2 G dev(D) integrated with a
// rotation that stays orthogonal for any spin increment. The pressure comes
// from the equation of state (eos.hpp), so the stress is sigma = s - p I.
#pragma once

#include <cmath>

#include "solver/common/types.hpp"

namespace splat {

inline Mat3 deviator(const Mat3& a) {
  return a - (a.trace() / 3.0) * Mat3::Identity();
}

// von Mises equivalent stress q = sqrt(3/2 s:s) of a deviatoric tensor.
inline double von_mises(const Mat3& s_dev) {
  return std::sqrt(1.5 * s_dev.squaredNorm());
}

// Rotates a tensor by the incremental Hughes-Winget rotation of spin W over dt.
inline Mat3 jaumann_rotate(const Mat3& s, const Mat3& W, double dt) {
  const Mat3 half = 0.5 * dt * W;
  const Mat3 Q = (Mat3::Identity() - half).inverse() * (Mat3::Identity() + half);
  return Q * s * Q.transpose();
}

}  // namespace splat
