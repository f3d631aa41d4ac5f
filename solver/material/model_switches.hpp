// Switches a scene or the material-point driver may turn off; each removes the
// work of its term entirely, in every strength law.
#pragma once

namespace splat {

struct ModelSwitches {
  bool damage = true;             // damage initiation and evolution
  bool thermal_softening = true;  // temperature dependence of the flow stress (at T_ref when off)
  bool rate_hardening = true;     // rate dependence of the flow stress (at eps_dot_0 when off)
  bool adiabatic_heating = true;  // plastic work raises the temperature
  bool heat_conduction = false;   // heat flows between elements (with a conductivity given)
};

}  // namespace splat
