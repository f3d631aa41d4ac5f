// Nonlocal average of the interface state over a physical length, so that
// link activation and erosion read a property of the interface, not of the
// single element that happens to carry a node.
//
// Each interface sample j (a slave node in a contact pair) carries its
// position x_j (m), its adhesive area A_j (m^2) and the raw state of both
// sides: the yield ratio sigma_y_static / sigma_y_static_peak (-) and the
// damage D (-). The averaged state of sample k is
//   <q>_k = sum_j w_kj q_j / sum_j w_kj,   w_kj = A_j max(0, 1 - |x_j - x_k| / l)
// (a hat of radius l, Bazant and Jirasek 2002's nonlocal integral form with a
// truncated cone weight, restricted to the interface). The sample itself always
// counts (w_kk = A_k), so with l below the node spacing, or l = 0, each sample
// keeps its own state. A localised spike of width h < l enters the average with
// weight ~ h / l: the average converges as the mesh is refined while the peak
// does not (thesis 2.2.2 reads the peak).
#pragma once

#include <vector>

#include "solver/common/types.hpp"

namespace splat {

// The state of one side of the interface at one sample, or its average.
struct InterfaceSideState {
  double yield_ratio = 1.0;  // sigma_y_static / sigma_y_static_peak, -
  double damage = 0.0;       // D, -
  // Current rate-free yield stress sigma_y_static, Pa; a side without
  // material (rigid) is taken as 1e30 Pa, stronger than any bond.
  double flow_stress = 1e30;
};

struct InterfaceSample {
  Vec3 x = Vec3::Zero();  // m
  double area = 0.0;      // m^2 (any common scale: per radian in axisymmetric runs)
  InterfaceSideState slave;
  InterfaceSideState master;
};

struct InterfaceAverage {
  InterfaceSideState slave;
  InterfaceSideState master;
};

// The averaged state of every sample, in the order given; `length` is l (m).
std::vector<InterfaceAverage> average_interface(const std::vector<InterfaceSample>& samples,
                                                double length);

}  // namespace splat
