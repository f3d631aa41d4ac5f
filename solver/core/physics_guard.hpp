// Physics checks a run must pass before it may report a verdict. A run whose
// physics broke (a body through the other, energy created) ends `unstable`
// with the check's name and figures instead of a stick or rebound.
//
// Interpenetration. For every live node of the particle (FE node or SPH
// particle centre) that lies inside a live element of an FE substrate, the
// depth is its distance to the substrate's live contact surface (master
// faces of the interface). The check fails when a depth exceeds
// k_interpenetration_limit times the characteristic length of the element
// holding the node: contact keeps a node on the surface to within a small
// fraction of an element, so a node an element-half deep has gone through.
//
// SPH substrate (the particle is then SPH too: contact pairs SPH masters with
// SPH slaves only). Contact keeps two particles of the bodies at least their
// pinball radii apart, r_p + r_s = (d_p + d_s) / 2 (the spacings' halves),
// so the depth of a live particle is how far its nearest live substrate
// particle is inside that distance. A particle has gone through when that
// depth exceeds k_interpenetration_limit times the substrate spacing d_s, or
// when it is enclosed: at least k_enclosure_neighbours live substrate
// particles within k_enclosure_radius d_s, in directions that nearly cancel
// (|sum of unit vectors| below k_enclosure_balance times their count). A
// particle resting on the surface or in a crater has its substrate
// neighbours on one side (balance 0.5-0.9); on the cubic lattice, one
// sitting flush in the top layer (substrate below and beside it) has 0.29,
// one buried a layer deeper (substrate all round) 0; the limit, 0.15, is
// halfway: closer to buried than to flush.
// Deactivated SPH particles (no stress left) take no part.
// Rigid walls are not checked (the figures then read "not checked").
//
// Energy. The eroded energy (kinetic + internal energy the erosion took out)
// and the internal energy are sums of non-negative terms; either below
// -energy_limit x the reference energy means the bookkeeping broke. The
// plastic work is part of the internal energy (each point's energy is the
// work of its stresses, elastic plus plastic), so plastic work - internal -
// eroded energy stays at or below 0 but for the stress update's own energy
// error; above energy_limit x the reference energy the strength law booked
// more plastic work, and heat, than the stresses received. The radial return
// books sigma_y dp for every step's plastic increment while the stress work
// of a step whose strain increment reverses the deviator is near 0, so
// strain increments that flip from step to step (particle-scale noise) heat
// and soften the metal without mechanical work (copper, shear increments of
// 0.05 reversing every step: 27 times the stress work; monotonic: 1.026
// times, 1.002 at 0.01; tests/unit/test_plastic_work_booking.cpp).
// Measured (Al/Al, plastic work minus internal energy over the initial
// energy): FE axisymmetric at 800 m/s -3.0 % and -1.1 % (8 and 16 across);
// the SPH Taylor bar 0.0 %; the SPH quarter impact at 400 m/s -0.4 / -0.6 %,
// 600 m/s -0.1 / -0.3 %, 800 m/s +4.8 / +3.0 % (6 / 10 spacings across R;
// docs/verification.md, SPH, for the contact that kicked its surface
// particles to +20 %).
#pragma once

#include <optional>
#include <string>

#include "solver/core/model_builder.hpp"
#include "solver/core/run_summary.hpp"

namespace splat {

// Depth over the local element size above which a node has gone through, -.
inline constexpr double k_interpenetration_limit = 0.5;
// Enclosure of a particle by SPH substrate particles (above).
inline constexpr double k_enclosure_radius = 1.5;    // neighbourhood radius / d_s, -
inline constexpr int k_enclosure_neighbours = 6;     // fewest neighbours to count as enclosed
inline constexpr double k_enclosure_balance = 0.15;  // |sum of unit vectors| / count, -

struct GuardInput {
  int particle = -1;          // scene body index of the particle
  int substrate = -1;         // scene body index of the substrate, -1: rigid wall
  int contact = -1;           // contact interface index, -1: none
  double energy_limit = 0.0;  // the scene's energy_balance_limit, -
};

// Deepest live particle node inside a live FE substrate element, or deepest
// pinball overlap on an SPH substrate (above), and how many nodes went
// through.
struct Interpenetration {
  bool checked = false;
  bool sph = false;        // measured on an SPH substrate
  double max_depth = 0.0;  // m
  double max_ratio = 0.0;  // depth / element characteristic length (SPH: spacing), -
  long long nodes_through = 0;
  double time = -1.0;  // s, when it was measured (-1: at the end of the run)
};
Interpenetration measure_interpenetration(const Model& model, const GuardInput& in);

// The worse of two measures: more nodes through, else the deeper ratio.
Interpenetration worse(const Interpenetration& a, const Interpenetration& b);

// Checks `model` and `energy`; fills `figures` (always) and returns the first
// failed check (none when all pass), with its reason in `reason`. The
// interpenetration check takes the worse of the end state and `during`, the
// worst state sampled while the run went on (a particle node that went
// through the substrate and came back out broke the contact as surely as one
// still inside).
std::optional<StopReason> check_physics(const Model& model, const EnergyBudget& energy,
                                        const GuardInput& in, GuardFigures& figures,
                                        std::string& reason,
                                        const Interpenetration& during = Interpenetration{});

}  // namespace splat
