// Heat conduction between the elements of an FE body: Fourier's law,
// rho c_p dT/dt = div(k grad T), by finite volumes on the element centres.
// Each face two active elements share carries the heat
//   Q = G (T_b - T_a) dt,  G = k A / d,
// A the face's current area (axisymmetric: its length times its mean radius,
// per radian), d the distance between the two elements' centres (the mean of
// their nodes). An element's heat capacity is rho0 c_p V0, so the scheme
// conserves the body's heat to rounding and is stable (no new extremum) for
//   dt <= rho0 c_p V0 / sum of its faces' G.
// k is the material's room-temperature conductivity; no heat crosses a
// contact interface or the body's free surface (adiabatic boundaries), and
// an eroded element conducts no heat.
//
// Why: a cold-spray interface softens in a shear band that adiabatic
// plasticity makes as thin as one element, whatever the element size; heat
// conduction gives it a physical width, of the order of sqrt(k t / (rho c_p))
// over the time t of the impact (about 1 um for aluminium over 10 ns), so that
// the softening that activates the bonds converges once the mesh resolves it.
#pragma once

#include "solver/fe/fe_body.hpp"

namespace splat {

// Whether `body` conducts heat: its switch is on and its material gives a
// conductivity and a heat capacity.
bool conducts_heat(const FeBody& body);

// Finds the faces each element shares with another (HeatFace), for a body
// that conducts heat; leaves the lists empty for one that does not.
void build_heat_faces(FeBody& body);

// Moves heat between the active elements of `body` over dt (0: no heat moves)
// on the current node positions: each element's temperature, internal energy
// and strength caches follow (add_heat). Returns the largest stable dt of the
// scheme on the current geometry, s (+infinity for a body that conducts no
// heat).
double fe_conduct_heat(FeBody& body, const NodeSet& nodes, double dt);

}  // namespace splat
