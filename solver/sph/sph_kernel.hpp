// SPH smoothing kernels in 3D, both with compact support of radius 2h (q = r/h
// in [0, 2]), normalised so that the integral of W over space is 1.
//
// M4 cubic spline (Monaghan & Lattanzio 1985; the thesis's eq. 1.12 is
// garbled in the text we have, this is the standard form it intends):
//   W(q) = sigma / h^3 * { 1 - 3/2 q^2 + 3/4 q^3     0 <= q <= 1
//                        { 1/4 (2 - q)^3             1 <  q <= 2
//   sigma = 1 / pi                                   (3D)
// Wendland C2 (Wendland 1995, Dehnen & Aly 2012, written for support 2h):
//   W(q) = 21 / (16 pi h^3) (1 - q/2)^4 (2 q + 1)    0 <= q <= 2
//
// In the thesis the "SPH particle radius" R is half the particle spacing and
// the smoothing length is h = 2 R (the kernel reaches 4 R = 2 spacings), with
// about 50 neighbours on a hexagonal-close-packed lattice: our default
// h = 1.0 x spacing is that choice.
#pragma once

#include <numbers>

namespace splat {

enum class SphKernel { cubic_spline, wendland_c2 };

// Kernel value and radial derivative at distance r.
struct KernelValue {
  double w = 0.0;      // W, 1/m^3
  double dw_dr = 0.0;  // dW/dr (<= 0), 1/m^4
};

inline KernelValue cubic_spline(double r, double h) {
  const double q = r / h;
  const double sigma = 1.0 / (std::numbers::pi * h * h * h);
  KernelValue k;
  if (q < 1.0) {
    k.w = sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    k.dw_dr = sigma / h * (-3.0 * q + 2.25 * q * q);
  } else if (q < 2.0) {
    const double t = 2.0 - q;
    k.w = sigma * 0.25 * t * t * t;
    k.dw_dr = -sigma / h * 0.75 * t * t;
  }
  return k;
}

inline KernelValue wendland_c2(double r, double h) {
  const double q = r / h;
  KernelValue k;
  if (q < 2.0) {
    const double sigma = 21.0 / (16.0 * std::numbers::pi * h * h * h);
    const double t = 1.0 - 0.5 * q;
    const double t3 = t * t * t;
    k.w = sigma * t3 * t * (2.0 * q + 1.0);
    // d/dq [t^4 (2q + 1)] = -2 t^3 (2q + 1) + 2 t^4 = -5 q t^3
    k.dw_dr = -sigma / h * 5.0 * q * t3;
  }
  return k;
}

inline KernelValue kernel(SphKernel type, double r, double h) {
  return type == SphKernel::cubic_spline ? cubic_spline(r, h) : wendland_c2(r, h);
}

// Support radius of both kernels, in units of h.
constexpr double kernel_support = 2.0;  // -

}  // namespace splat
