#include "solver/input/material_io.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>

#include "solver/input/embedded.hpp"

namespace splat {

using nlohmann::json;

namespace {

constexpr std::string_view schema_name = "material";

// Value at `pointer` if it is a number (the schema may have rejected it).
std::optional<double> number_at(const json& doc, const char* pointer) {
  const json::json_pointer p(pointer);
  if (!doc.contains(p)) return std::nullopt;
  const json& v = doc.at(p);
  return v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
}

std::string string_at(const json& doc, const char* pointer) {
  const json::json_pointer p(pointer);
  return doc.contains(p) && doc.at(p).is_string() ? doc.at(p).get<std::string>() : std::string();
}

bool rejected(const std::vector<SchemaViolation>& v, std::string_view pointer) {
  return std::any_of(v.begin(), v.end(),
                     [&](const SchemaViolation& x) { return x.pointer == pointer; });
}

// The value at `later` must be > (strictly_greater) or <= the value at
// `earlier`; nothing is said when either is absent or already rejected by
// the schema. `earlier_default` stands in for an absent optional field.
void check_order(const json& doc, const std::vector<SchemaViolation>& schema_errors,
                 const char* earlier, const char* later, bool strictly_greater,
                 std::string_view words, std::vector<SchemaViolation>& out,
                 std::optional<double> earlier_default = {}) {
  if (rejected(schema_errors, earlier) || rejected(schema_errors, later)) return;
  const std::optional<double> a =
      number_at(doc, earlier) ? number_at(doc, earlier) : earlier_default;
  const std::optional<double> b = number_at(doc, later);
  if (!a || !b) return;
  const bool ok = strictly_greater ? *b > *a : *b <= *a;
  if (!ok) out.push_back({later, std::string(words)});
}

DamageInitiation initiation_of(const std::string& s) {
  if (s == "johnson-cook") return DamageInitiation::johnson_cook;
  if (s == "shear") return DamageInitiation::shear;
  return DamageInitiation::none;
}

const char* initiation_name(DamageInitiation d) {
  switch (d) {
    case DamageInitiation::none:
      return "none";
    case DamageInitiation::johnson_cook:
      return "johnson-cook";
    case DamageInitiation::shear:
      return "shear";
  }
  return "none";
}

DamageEvolution evolution_of(const std::string& s) {
  if (s == "instant") return DamageEvolution::instant;
  if (s == "fracture-energy") return DamageEvolution::fracture_energy;
  return DamageEvolution::plastic_strain;
}

const char* evolution_name(DamageEvolution d) {
  switch (d) {
    case DamageEvolution::instant:
      return "instant";
    case DamageEvolution::plastic_strain:
      return "plastic-strain";
    case DamageEvolution::fracture_energy:
      return "fracture-energy";
  }
  return "plastic-strain";
}

void read_cubic(const json& a, double (&c)[4]) {
  for (std::size_t i = 0; i < 4; ++i) c[i] = a.at(i).get<double>();
}

json cubic_json(const double (&c)[4]) {
  return json::array({c[0], c[1], c[2], c[3]});
}

bool same_cubic(const double (&a)[4], const double (&b)[4]) {
  return std::equal(std::begin(a), std::end(a), std::begin(b));
}

// True when `d` is the state of a material without a "damage" block.
bool is_no_damage(const DamageParams& d) {
  const DamageParams none;
  const JohnsonCookFailureParams& j = d.jc;
  const ShearFailureParams& s = d.shear;
  return d.initiation == none.initiation && d.evolution == none.evolution &&
         d.eps_p_max == none.eps_p_max && d.G_f == none.G_f && d.D_max == none.D_max &&
         d.initial_random_max == none.initial_random_max && j.D1 == none.jc.D1 &&
         j.D2 == none.jc.D2 && j.D3 == none.jc.D3 && j.D4 == none.jc.D4 && j.D5 == none.jc.D5 &&
         s.k_s == none.shear.k_s && s.theta_min == none.shear.theta_min &&
         s.theta_max == none.shear.theta_max && s.rate_low == none.shear.rate_low &&
         s.rate_high == none.shear.rate_high && same_cubic(s.low, none.shear.low) &&
         same_cubic(s.high, none.shear.high);
}

// Calls fn(Law{}) for the alternative of StrengthModel whose "model" name is
// `model`; false when there is none.
template <class F>
bool with_law_named(const std::string& model, F&& fn) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return ((std::variant_alternative_t<I, StrengthModel>::model == model &&
             (fn(std::variant_alternative_t<I, StrengthModel>{}), true)) ||
            ...);
  }
  (std::make_index_sequence<std::variant_size_v<StrengthModel>>{});
}

StrengthModel strength_from_json(const json& st) {
  StrengthModel out;
  with_law_named(st.at("model").get<std::string>(), [&](auto law) {
    for (const auto& f : law.fields()) law.*f.member = st.at(f.name).template get<double>();
    out = law;
  });
  return out;
}

json strength_to_json(const StrengthModel& strength) {
  return std::visit(
      [](const auto& law) {
        json st = {{"model", law.model}};
        for (const auto& f : law.fields()) st[f.name] = law.*f.member;
        return st;
      },
      strength);
}

// What metals have: a value outside [lo, hi] is refused, and the units a
// slip most likely wrote it in are named.
struct MagnitudeRange {
  double lo, hi;       // bounds, in the unit
  bool zero_ok;        // 0 is a meaningful value too (no hardening)
  const char* unit;    // the unit the document uses
  const char* bounds;  // lo and hi in words
};

// A unit a value may have been written in by mistake: value * to_si +
// offset is the value in si_unit.
struct UnitSlip {
  const char* unit;
  const char* si_unit;
  double to_si;
  double offset;
};

inline constexpr UnitSlip unit_slips[] = {
    {"MPa", "Pa", 1e6, 0.0},
    {"GPa", "Pa", 1e9, 0.0},
    {"kPa", "Pa", 1e3, 0.0},
    {"MPa multiplied by 1e6 twice", "Pa", 1e-6, 0.0},
    {"g/cm^3", "kg/m^3", 1e3, 0.0},
    {"degrees Celsius", "K", 1.0, 273.15},
    {"kJ/(kg K)", "J/(kg K)", 1e3, 0.0},
    {"g/mol", "kg/mol", 1e-3, 0.0},
    {"1/GPa", "1/Pa", 1e-9, 0.0},
    {"1/Mbar", "1/Pa", 1e-11, 0.0},
};

std::optional<MagnitudeRange> metal_range(Quantity q) {
  switch (q) {
    case Quantity::yield_stress:
      return MagnitudeRange{1e6, 1e10, false, "Pa", "1 MPa to 10 GPa"};
    case Quantity::hardening_stress:
      return MagnitudeRange{1e6, 1e10, true, "Pa", "0 or 1 MPa to 10 GPa"};
    case Quantity::room_temperature:
      return MagnitudeRange{50.0, 1500.0, false, "K", "50 K to 1500 K"};
    case Quantity::melting_temperature:
      return MagnitudeRange{300.0, 4500.0, false, "K", "300 K to 4500 K"};
    case Quantity::shear_modulus:
      return MagnitudeRange{1e9, 1e12, false, "Pa", "1 GPa to 1000 GPa"};
    case Quantity::density:
      return MagnitudeRange{500.0, 25000.0, false, "kg/m^3", "500 to 25000 kg/m^3"};
    case Quantity::molar_mass:
      return MagnitudeRange{0.006, 0.3, false, "kg/mol", "0.006 to 0.3 kg/mol"};
    case Quantity::inverse_pressure:
      return MagnitudeRange{1e-12, 1e-9, true, "1/Pa", "0 or 1e-12 to 1e-9 1/Pa"};
    case Quantity::dimensionless:
    case Quantity::rate:
    case Quantity::inverse_temperature:
      break;
  }
  return std::nullopt;
}

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// The refusal of `value` at `pointer`, or nothing when it is in range.
void check_magnitude(const json& doc, const std::vector<SchemaViolation>& schema_errors,
                     const std::string& pointer, const MagnitudeRange& r,
                     std::vector<SchemaViolation>& out) {
  if (rejected(schema_errors, pointer)) return;
  const std::optional<double> v = number_at(doc, pointer.c_str());
  if (!v) return;
  const auto inside = [&](double x) { return (r.zero_ok && x == 0.0) || (x >= r.lo && x <= r.hi); };
  if (inside(*v)) return;
  std::string hint;
  for (const UnitSlip& u : unit_slips) {
    const double si = *v * u.to_si + u.offset;
    if (std::string_view(u.si_unit) == r.unit && inside(si)) {
      hint = "; if it was meant in " + std::string(u.unit) + ", write " + number_text(si);
      break;
    }
  }
  out.push_back({pointer, number_text(*v) + " " + r.unit + " is outside what metals have (" +
                              r.bounds + ")" + hint});
}

// Density, Young's modulus, specific heat and the strength law's stresses and
// temperatures against what metals have (unit slips, e.g. "A": 163 where MPa
// was meant, pass the schema's bounds).
void check_metal_magnitudes(const json& doc, const std::vector<SchemaViolation>& schema_errors,
                            std::vector<SchemaViolation>& out) {
  check_magnitude(doc, schema_errors, "/density",
                  {500.0, 25000.0, false, "kg/m^3", "500 to 25000 kg/m^3"}, out);
  check_magnitude(doc, schema_errors, "/elastic/E", {1e9, 1.5e12, false, "Pa", "1 GPa to 1500 GPa"},
                  out);
  check_magnitude(doc, schema_errors, "/thermal/c_p",
                  {50.0, 5000.0, false, "J/(kg K)", "50 to 5000 J/(kg K)"}, out);
  check_magnitude(doc, schema_errors, "/thermal/conductivity",
                  {1.0, 1000.0, false, "W/(m K)", "1 to 1000 W/(m K)"}, out);
  with_law_named(string_at(doc, "/strength/model"), [&](const auto& law) {
    for (const auto& f : law.fields()) {
      if (const std::optional<MagnitudeRange> r = metal_range(f.quantity)) {
        check_magnitude(doc, schema_errors, std::string("/strength/") + f.name, *r, out);
      }
    }
  });
}

}  // namespace

std::vector<SchemaViolation> material_violations(const json& doc) {
  std::vector<SchemaViolation> out = validate(schema_name, doc);
  const std::vector<SchemaViolation> schema_errors = out;
  check_order(doc, schema_errors, "/strength/T_ref", "/strength/T_melt", true,
              "must be > T_ref (K)", out);
  if (doc.is_object()) check_metal_magnitudes(doc, schema_errors, out);
  if (doc.is_object() && doc.contains("damage")) {
    check_order(doc, schema_errors, "/damage/D_max", "/damage/initial_random_max", false,
                "must be <= D_max (-)", out, DamageParams{}.D_max);
    if (string_at(doc, "/damage/initiation/model") == "shear") {
      check_order(doc, schema_errors, "/damage/initiation/theta_min",
                  "/damage/initiation/theta_max", true, "must be > theta_min (-)", out);
      check_order(doc, schema_errors, "/damage/initiation/rate_low", "/damage/initiation/rate_high",
                  true, "must be > rate_low (1/s)", out);
    }
  }
  return out;
}

Material material_from_json(const json& doc) {
  std::vector<SchemaViolation> problems = material_violations(doc);
  if (!problems.empty()) throw InputError(std::move(problems));

  Material m;
  m.name = doc.at("name").get<std::string>();
  m.source = doc.at("source").get<std::string>();
  m.density = doc.at("density").get<double>();

  const json& el = doc.at("elastic");
  m.elastic.E = el.at("E").get<double>();
  m.elastic.nu = el.at("nu").get<double>();

  m.strength = strength_from_json(doc.at("strength"));

  const json& th = doc.at("thermal");
  m.thermal.c_p = th.at("c_p").get<double>();
  m.thermal.heat_fraction = th.value("heat_fraction", m.thermal.heat_fraction);
  m.thermal.conductivity = th.value("conductivity", 0.0);

  const json& eos = doc.at("eos");
  m.eos.model = eos.at("model").get<std::string>() == "mie-gruneisen" ? EosModel::mie_gruneisen
                                                                      : EosModel::linear;
  if (eos.contains("mie_gruneisen")) {
    const json& mg = eos.at("mie_gruneisen");
    m.eos.mie_gruneisen = MieGruneisenParams{mg.at("c0").get<double>(), mg.at("s").get<double>(),
                                             mg.at("gamma0").get<double>()};
  }

  if (doc.contains("damage")) {
    const json& dm = doc.at("damage");
    DamageParams& d = m.damage;
    const json& ini = dm.at("initiation");
    d.initiation = initiation_of(ini.at("model").get<std::string>());
    if (d.initiation == DamageInitiation::johnson_cook) {
      d.jc = {ini.at("D1").get<double>(), ini.at("D2").get<double>(), ini.at("D3").get<double>(),
              ini.at("D4").get<double>(), ini.at("D5").get<double>()};
    } else if (d.initiation == DamageInitiation::shear) {
      ShearFailureParams& s = d.shear;
      s.k_s = ini.at("k_s").get<double>();
      s.theta_min = ini.at("theta_min").get<double>();
      s.theta_max = ini.at("theta_max").get<double>();
      s.rate_low = ini.at("rate_low").get<double>();
      s.rate_high = ini.at("rate_high").get<double>();
      read_cubic(ini.at("low"), s.low);
      read_cubic(ini.at("high"), s.high);
    }
    const json& evo = dm.at("evolution");
    d.evolution = evolution_of(evo.at("model").get<std::string>());
    if (d.evolution == DamageEvolution::plastic_strain) {
      d.eps_p_max = evo.at("eps_p_max").get<double>();
    } else if (d.evolution == DamageEvolution::fracture_energy) {
      d.G_f = evo.at("G_f").get<double>();
    }
    d.D_max = dm.value("D_max", d.D_max);
    d.initial_random_max = dm.value("initial_random_max", d.initial_random_max);
  }
  return m;
}

json material_to_json(const Material& m) {
  json doc = {
      {"name", m.name},
      {"source", m.source},
      {"density", m.density},
      {"elastic", {{"E", m.elastic.E}, {"nu", m.elastic.nu}}},
      {"strength", strength_to_json(m.strength)},
      {"thermal", {{"c_p", m.thermal.c_p}, {"heat_fraction", m.thermal.heat_fraction}}},
  };
  if (m.thermal.conductivity > 0.0) doc["thermal"]["conductivity"] = m.thermal.conductivity;
  json eos = {{"model", m.eos.model == EosModel::mie_gruneisen ? "mie-gruneisen" : "linear"}};
  if (m.eos.mie_gruneisen) {
    const MieGruneisenParams& mg = *m.eos.mie_gruneisen;
    eos["mie_gruneisen"] = {{"c0", mg.c0}, {"s", mg.s}, {"gamma0", mg.gamma0}};
  }
  doc["eos"] = eos;

  const DamageParams& d = m.damage;
  if (!is_no_damage(d)) {
    json ini = {{"model", initiation_name(d.initiation)}};
    if (d.initiation == DamageInitiation::johnson_cook) {
      ini.update(
          {{"D1", d.jc.D1}, {"D2", d.jc.D2}, {"D3", d.jc.D3}, {"D4", d.jc.D4}, {"D5", d.jc.D5}});
    } else if (d.initiation == DamageInitiation::shear) {
      const ShearFailureParams& s = d.shear;
      ini.update({{"k_s", s.k_s},
                  {"theta_min", s.theta_min},
                  {"theta_max", s.theta_max},
                  {"rate_low", s.rate_low},
                  {"rate_high", s.rate_high},
                  {"low", cubic_json(s.low)},
                  {"high", cubic_json(s.high)}});
    }
    json evo = {{"model", evolution_name(d.evolution)}};
    if (d.evolution == DamageEvolution::plastic_strain) evo["eps_p_max"] = d.eps_p_max;
    if (d.evolution == DamageEvolution::fracture_energy) evo["G_f"] = d.G_f;
    doc["damage"] = {{"initiation", ini},
                     {"evolution", evo},
                     {"D_max", d.D_max},
                     {"initial_random_max", d.initial_random_max}};
  }
  return doc;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const EmbeddedText& e : embedded_materials()) names.emplace_back(e.name);
  std::sort(names.begin(), names.end());
  return names;
}

json material_document(std::string_view name_or_path) {
  const std::string name(name_or_path);
  for (const EmbeddedText& e : embedded_materials()) {
    if (e.name == name) return parse_json_text(e.text, "library material '" + name + "'");
  }
  const std::filesystem::path path(name);
  std::error_code ec;
  const bool looks_like_path = name.find('/') != std::string::npos ||
                               name.find('\\') != std::string::npos || path.extension() == ".json";
  if (looks_like_path || std::filesystem::exists(path, ec)) return read_json_file(path);
  std::string known;
  for (const std::string& n : material_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError({{"", "unknown material '" + name + "' (known: " + known +
                             "; or give a path to a JSON file)"}});
}

Material load_material(std::string_view name_or_path) {
  return material_from_json(material_document(name_or_path));
}

namespace {

std::string escaped_token(const std::string& key) {
  std::string out;
  for (char ch : key) out += ch == '~' ? "~0" : ch == '/' ? "~1" : std::string(1, ch);
  return out;
}

bool is_library_material(const std::string& name) {
  const std::vector<std::string> names = material_names();
  return std::binary_search(names.begin(), names.end(), name);
}

void find_non_library_materials(const json& doc, const std::string& pointer,
                                std::vector<MaterialReference>& out) {
  if (doc.is_array()) {
    for (std::size_t i = 0; i < doc.size(); ++i)
      find_non_library_materials(doc[i], pointer + "/" + std::to_string(i), out);
    return;
  }
  if (!doc.is_object()) return;
  for (const auto& [key, value] : doc.items()) {
    const std::string p = pointer + "/" + escaped_token(key);
    const json* name = nullptr;
    std::string where = p;
    if (key == "material" && value.is_string()) name = &value;
    if (key == "material" && value.is_object() && value.contains("base") &&
        value["base"].is_string()) {
      name = &value["base"];
      where = p + "/base";
    }
    if (name && !is_library_material(name->get<std::string>())) {
      out.push_back({where, name->get<std::string>()});
    } else if (!name) {
      find_non_library_materials(value, p, out);
    }
  }
}

}  // namespace

std::vector<MaterialReference> non_library_materials(const json& doc) {
  std::vector<MaterialReference> out;
  find_non_library_materials(doc, "", out);
  return out;
}

}  // namespace splat
