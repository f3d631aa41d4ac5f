#include "solver/input/adhesion_io.hpp"

#include <string>

namespace splat {

using nlohmann::json;

AdhesionParams adhesion_from_json(const json& j) {
  AdhesionParams p;
  p.G_c = j.at("G_c").get<double>();
  // sigma_c: a number (Pa), null (no cap) or "flow-stress", the default.
  const auto s = j.find("sigma_c");
  if (s == j.end() || (s->is_string() && s->get<std::string>() == "flow-stress")) {
    p.cap_at_flow_stress = true;
  } else if (s->is_number()) {
    p.sigma_c = s->get<double>();
  }
  if (const auto d = j.find("D_adh_max"); d != j.end() && !d->is_null()) {
    p.D_adh_max = d->get<double>();
  }
  p.averaging_length = j.value("averaging_length", k_default_averaging_length);
  if (const auto a = j.find("activation"); a != j.end()) {
    p.activation =
        parse<ActivationRule>(a->value("rule", std::string("none"))).value_or(ActivationRule::none);
    p.yield_drop = a->value("drop_percent", 0.0) / 100.0;
    p.homologous_temperature = a->value("homologous_temperature", 1.0);
    p.surface_expansion = a->value("surface_expansion", 1.0);
    p.sides = a->value("sides", std::string("either")) == "both" ? ActivationSides::both
                                                                 : ActivationSides::either;
    // The films crack on the surface expansion, so that rule bonds the
    // metal through the cracks unless the scene says otherwise.
    const BondedFraction by_default = p.activation == ActivationRule::surface_expansion
                                          ? BondedFraction::film_cracks
                                          : BondedFraction::full;
    p.bonded_fraction =
        parse<BondedFraction>(a->value("bonded_fraction", std::string(to_string(by_default))))
            .value_or(by_default);
  }
  return p;
}

json adhesion_to_json(const AdhesionParams& p) {
  json activation{{"rule", std::string(to_string(p.activation))},
                  {"drop_percent", p.yield_drop * 100.0},
                  {"sides", p.sides == ActivationSides::both ? "both" : "either"}};
  if (p.activation == ActivationRule::temperature) {
    activation["homologous_temperature"] = p.homologous_temperature;
  }
  if (p.activation == ActivationRule::surface_expansion) {
    activation["surface_expansion"] = p.surface_expansion;
    activation["bonded_fraction"] = std::string(to_string(p.bonded_fraction));
  }
  return {{"G_c", p.G_c},
          {"sigma_c", p.cap_at_flow_stress ? json("flow-stress")
                      : p.sigma_c          ? json(*p.sigma_c)
                                           : json(nullptr)},
          {"activation", std::move(activation)},
          {"D_adh_max", p.D_adh_max ? json(*p.D_adh_max) : json(nullptr)},
          {"averaging_length", p.averaging_length}};
}

}  // namespace splat
