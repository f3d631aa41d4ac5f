// Nonlocal average of the material state next to the interface over a
// physical length, so that link activation, erosion and the bond's strength
// read a property of the material around a contact point, not of the single
// element that happens to carry a node.
//
// The points j are the material points of one side (element centres of an
// FE body, particles of an SPH body) with position x_j (m), weight V_j (their
// volume, m^3, or any common scale: per radian in axisymmetric runs) and state
// q_j (InterfaceSideState: the yield ratio, damage, flow stress and
// homologous temperature of the point). The state around a centre c_k (a contact
// point) is
//   <q>_k = sum_j w_kj q_j / sum_j w_kj,   w_kj = V_j max(0, 1 - |x_j - c_k| / l)
// (the nonlocal integral form with a truncated-cone weight, Bazant and
// Jirasek 2002, J. Eng. Mech. 128(11), eq. 1, over the side's volume within l
// of the contact point). It averages both along the interface and into the
// material: the softened layer of an adiabatic shear band at the interface is
// about one element thick, its peak grows as the mesh is refined, while its
// weight in the average shrinks with it, so the average converges. A centre
// with no point within l (l below half the element size) keeps its fallback
// state (the node's own elements).
#pragma once

#include <vector>

#include "solver/common/types.hpp"
#include "solver/material/point_update.hpp"

namespace splat {

// The state of one side of the interface at one point, or its average: what
// link activation, erosion and the strength cap read (cohesive_law.hpp). The
// defaults are a side without material (rigid): it never softens, heats or
// fails, and is stronger than any bond.
struct InterfaceSideState {
  double yield_ratio = 1.0;             // sigma_y_static / sigma_y_static_peak, -
  double damage = 0.0;                  // D, -
  double flow_stress = 1e30;            // current rate-free yield stress sigma_y_static, Pa
  double homologous_temperature = 0.0;  // T / T_melt, -
  // Bay's surface expansion (A - A0) / A of the side's surface at the contact
  // point, -: a property of the surface, not of the material behind it, so
  // the contact stage sets it from the surface geometry after the average
  // (material samples carry 0).
  double surface_expansion = 0.0;
};

// The state of a material point with state `st` of a material melting at
// T_melt (K).
InterfaceSideState side_state(const PointState& st, double T_melt);

// sum += w s, field by field (the weighted sums of an average).
void accumulate(InterfaceSideState& sum, double w, const InterfaceSideState& s);

// A weighted sum divided by its total weight w_sum > 0.
InterfaceSideState divided(const InterfaceSideState& sum, double w_sum);

struct MaterialSample {
  Vec3 x = Vec3::Zero();  // m
  double weight = 0.0;    // volume, m^3 (any common scale)
  InterfaceSideState state;
};

// The averaged state around each centre (`length` = l, m); `fallback[k]` for
// a centre with no sample within l, and for l = 0.
std::vector<InterfaceSideState> average_around(const std::vector<MaterialSample>& samples,
                                               const std::vector<Vec3>& centres, double length,
                                               const std::vector<InterfaceSideState>& fallback);

}  // namespace splat
