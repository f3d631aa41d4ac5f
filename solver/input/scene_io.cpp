#include "solver/input/scene_io.hpp"

#include "solver/input/impact_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <numbers>
#include <optional>
#include <string_view>
#include <utility>

#include "solver/common/enum_names.hpp"
#include "solver/input/adhesion_io.hpp"
#include "solver/input/impact_scene.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/mesh/mesh.hpp"

namespace splat {
namespace {

using nlohmann::json;

// Semantic problems found after schema validation, reported together.
struct Problems {
  std::vector<SchemaViolation> list;
  void add(std::string pointer, std::string message) {
    list.push_back({std::move(pointer), std::move(message)});
  }
  void add_all(std::vector<SchemaViolation> more) {
    for (SchemaViolation& v : more) list.push_back(std::move(v));
  }
};

std::string at(std::string_view base, std::string_view member) {
  return std::string(base) + "/" + std::string(member);
}
std::string at(std::string_view base, std::size_t index) {
  return std::string(base) + "/" + std::to_string(index);
}

Vec3 vec3(const json& a) {
  return Vec3(a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>());
}
json to_json_vec(const Vec3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

// The value at `key` of object `j`, or `fallback` when absent.
template <class T>
T value_or(const json& j, const char* key, T fallback) {
  const auto it = j.find(key);
  return it == j.end() ? fallback : it->get<T>();
}

const json& member_or_empty(const json& j, const char* key) {
  static const json empty = json::object();
  const auto it = j.find(key);
  return it == j.end() ? empty : *it;
}

// Enumerations and their JSON spellings; the schema restricts the strings.
constexpr NameTable<GeometryType, 5> geometry_names{{
    {GeometryType::sphere, "sphere"},
    {GeometryType::cylinder, "cylinder"},
    {GeometryType::box, "box"},
    {GeometryType::half_disc, "half-disc"},
    {GeometryType::rectangle, "rectangle"},
}};
constexpr NameTable<Discretization, 3> discretization_names{{
    {Discretization::fe_axisym, "fe-axisym"},
    {Discretization::fe_hex, "fe-hex"},
    {Discretization::sph, "sph"},
}};
constexpr NameTable<SectorKind, 3> sector_names{{
    {SectorKind::full, "full"},
    {SectorKind::half, "half"},
    {SectorKind::quarter, "quarter"},
}};
constexpr NameTable<HourglassType, 2> hourglass_names{{
    {HourglassType::viscous, "viscous"},
    {HourglassType::stiffness, "stiffness"},
}};
constexpr NameTable<BoundaryType, 4> boundary_type_names{{
    {BoundaryType::fixed, "fixed"},
    {BoundaryType::symmetry, "symmetry"},
    {BoundaryType::velocity, "velocity"},
    {BoundaryType::absorbing, "absorbing"},
}};
constexpr NameTable<InteractionType, 2> interaction_names{{
    {InteractionType::rigid_wall, "rigid-wall"},
    {InteractionType::contact, "contact"},
}};
constexpr NameTable<ContactMethod, 2> contact_method_names{{
    {ContactMethod::lagrange, "lagrange"},
    {ContactMethod::penalty, "penalty"},
}};
constexpr NameTable<ContactSolverKind, 2> contact_solver_names{{
    {ContactSolverKind::pgs, "pgs"},
    {ContactSolverKind::active_set, "active-set"},
}};

// Each table lists its enum's values in declaration order.
static_assert(names_in_order(geometry_names));
static_assert(names_in_order(discretization_names));
static_assert(names_in_order(sector_names));
static_assert(names_in_order(hourglass_names));
static_assert(names_in_order(boundary_type_names));
static_assert(names_in_order(interaction_names));
static_assert(names_in_order(contact_method_names));
static_assert(names_in_order(contact_solver_names));

template <class E, std::size_t N>
E from_name(const NameTable<E, N>& table, const std::string& s) {
  if (const std::optional<E> value = value_in(table, s)) return *value;
  throw std::logic_error("scene_io: '" + s + "' passed the schema but has no enum value");
}

template <class E, std::size_t N>
std::string name_of(const NameTable<E, N>& table, E e) {
  if (const std::optional<std::string_view> name = name_in(table, e)) return std::string(*name);
  throw std::logic_error("scene_io: enum value without a name");
}

// Boundary names of 3D (fe-hex, sph) bodies and of axisymmetric bodies.
constexpr std::array<std::pair<std::uint32_t, std::string_view>, 7> boundary_names_3d{{
    {boundary_x_min, "x_min"},
    {boundary_x_max, "x_max"},
    {boundary_y_min, "y_min"},
    {boundary_y_max, "y_max"},
    {boundary_z_min, "z_min"},
    {boundary_z_max, "z_max"},
    {boundary_curved, "curved"},
}};
constexpr std::array<std::pair<std::uint32_t, std::string_view>, 5> boundary_names_axisym{{
    {boundary_x_min, "axis"},
    {boundary_x_max, "outer"},
    {boundary_y_min, "bottom"},
    {boundary_y_max, "top"},
    {boundary_curved, "curved"},
}};

template <std::size_t N>
std::optional<std::uint32_t> boundary_bit(
    const std::array<std::pair<std::uint32_t, std::string_view>, N>& table, const std::string& s) {
  for (const auto& [bit, name] : table) {
    if (name == s) return bit;
  }
  return std::nullopt;
}

bool is_axisymmetric(Discretization d) {
  return d == Discretization::fe_axisym;
}

// ---------------------------------------------------------------- materials

// A library name as is; a path (or an existing file) relative to the scene
// file's folder; anything else as given, so that an unknown name is reported
// as such by material_document.
std::string locate_material(const std::string& name_or_path,
                            const std::filesystem::path& base_dir) {
  const std::vector<std::string> names = material_names();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end()) return name_or_path;
  const std::filesystem::path path(name_or_path);
  if (path.is_absolute() || base_dir.empty()) return name_or_path;
  const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                               name_or_path.find('\\') != std::string::npos ||
                               path.extension() == ".json";
  std::error_code ec;
  if (looks_like_path || std::filesystem::exists(base_dir / path, ec)) {
    return (base_dir / path).string();
  }
  return name_or_path;
}

// The document of a library material or material file; problems are
// reported at `pointer`.
std::optional<json> named_material_document(const std::string& name_or_path,
                                            const std::filesystem::path& base_dir,
                                            const std::string& pointer, Problems& problems) {
  try {
    return material_document(locate_material(name_or_path, base_dir));
  } catch (const InputError& e) {
    for (const SchemaViolation& v : e.violations()) problems.add(pointer, to_string(v));
  }
  return std::nullopt;
}

// The material of a document that sits in the scene at `pointer` (inline or
// merged); violations carry their full scene pointer.
std::optional<Material> material_in_scene(const json& doc, const std::string& pointer,
                                          Problems& problems) {
  std::vector<SchemaViolation> violations = material_violations(doc);
  if (!violations.empty()) {
    problems.add_all(prefixed(pointer, std::move(violations)));
    return std::nullopt;
  }
  return material_from_json(doc);
}

// The three forms of a body's "material": a library name or file path; an
// inline document; {"base": NAME, ...fields} merged into NAME's document as
// a JSON merge patch (RFC 7386).
std::optional<Material> resolve_material(const json& m, const std::filesystem::path& base_dir,
                                         const std::string& pointer, Problems& problems) {
  if (m.is_string()) {
    const std::string name = m.get<std::string>();
    const std::optional<json> doc = named_material_document(name, base_dir, pointer, problems);
    if (!doc) return std::nullopt;
    // Pointers inside a file are the file's own: name the file in the message.
    std::vector<SchemaViolation> violations = material_violations(*doc);
    for (const SchemaViolation& v : violations) {
      problems.add(pointer, "material '" + name + "': " + to_string(v));
    }
    if (!violations.empty()) return std::nullopt;
    return material_from_json(*doc);
  }
  const auto base = m.find("base");
  if (base == m.end()) return material_in_scene(m, pointer, problems);
  if (!base->is_string()) {
    problems.add(at(pointer, "base"), "must be a string (a library material name or file path)");
    return std::nullopt;
  }
  std::optional<json> merged =
      named_material_document(base->get<std::string>(), base_dir, at(pointer, "base"), problems);
  if (!merged) return std::nullopt;
  json patch = m;
  patch.erase("base");
  merged->merge_patch(patch);
  return material_in_scene(*merged, pointer, problems);
}

}  // namespace

Material scene_material(const json& m, const std::filesystem::path& base_dir,
                        const std::string& pointer) {
  Problems problems;
  const std::optional<Material> material = resolve_material(m, base_dir, pointer, problems);
  if (!problems.list.empty()) throw InputError(std::move(problems.list));
  return *material;
}

namespace {

// ---------------------------------------------------------------- bodies

Geometry parse_geometry(const json& g) {
  Geometry geo;
  geo.type = from_name(geometry_names, g.at("type").get<std::string>());
  switch (geo.type) {
    case GeometryType::sphere:
      geo.radius = g.at("radius").get<double>();
      geo.centre = vec3(g.at("centre"));
      break;
    case GeometryType::cylinder:
      geo.radius = g.at("radius").get<double>();
      geo.z_min = g.at("z_min").get<double>();
      geo.z_max = g.at("z_max").get<double>();
      break;
    case GeometryType::box:
      geo.lo = vec3(g.at("min"));
      geo.hi = vec3(g.at("max"));
      break;
    case GeometryType::half_disc:
      geo.radius = g.at("radius").get<double>();
      geo.centre = Vec3(0.0, 0.0, g.at("z_centre").get<double>());
      break;
    case GeometryType::rectangle:
      geo.radius = g.at("r_max").get<double>();
      geo.z_min = g.at("z_min").get<double>();
      geo.z_max = g.at("z_max").get<double>();
      break;
  }
  return geo;
}

json geometry_to_json(const Geometry& geo) {
  json g{{"type", name_of(geometry_names, geo.type)}};
  switch (geo.type) {
    case GeometryType::sphere:
      g["radius"] = geo.radius;
      g["centre"] = to_json_vec(geo.centre);
      break;
    case GeometryType::cylinder:
      g["radius"] = geo.radius;
      g["z_min"] = geo.z_min;
      g["z_max"] = geo.z_max;
      break;
    case GeometryType::box:
      g["min"] = to_json_vec(geo.lo);
      g["max"] = to_json_vec(geo.hi);
      break;
    case GeometryType::half_disc:
      g["radius"] = geo.radius;
      g["z_centre"] = geo.centre.z();
      break;
    case GeometryType::rectangle:
      g["r_max"] = geo.radius;
      g["z_min"] = geo.z_min;
      g["z_max"] = geo.z_max;
      break;
  }
  return g;
}

// Geometry allowed for the discretization and well formed.
void check_geometry(const BodySpec& b, const std::string& p, Problems& problems) {
  const std::string gp = at(p, "geometry");
  const std::string type = name_of(geometry_names, b.geometry.type);
  const std::string disc = name_of(discretization_names, b.discretization);
  const bool axisym = is_axisymmetric(b.discretization);
  if (b.geometry.type == GeometryType::box && axisym) {
    problems.add(at(gp, "type"), "box needs fe-hex discretization, not " + disc);
  }
  if ((b.geometry.type == GeometryType::half_disc || b.geometry.type == GeometryType::rectangle) &&
      !axisym) {
    problems.add(at(gp, "type"), type + " needs fe-axisym discretization, not " + disc);
  }
  if (b.geometry.type == GeometryType::sphere && axisym &&
      (b.geometry.centre.x() != 0.0 || b.geometry.centre.y() != 0.0)) {
    problems.add(at(gp, "centre"), "must lie on the axis (x = y = 0) for fe-axisym bodies (m)");
  }
  if ((b.geometry.type == GeometryType::cylinder || b.geometry.type == GeometryType::rectangle) &&
      !(b.geometry.z_max > b.geometry.z_min)) {
    problems.add(at(gp, "z_max"), "must be > z_min (m)");
  }
  if (b.geometry.type == GeometryType::box) {
    for (int i = 0; i < 3; ++i) {
      if (!(b.geometry.hi[i] > b.geometry.lo[i])) {
        const std::string index = std::to_string(i);
        problems.add(gp + "/max/" + index, "must be > min/" + index + " (m)");
      }
    }
  }
}

// grading.uniform_extent: half-widths of the zone at the base element size,
// m, [r, 0, z] for fe-axisym bodies; rectangle and box geometries only.
void parse_uniform_extent(const json& u, BodySpec& b, bool axisym, const std::string& up,
                          Problems& problems) {
  b.grading.uniform_extent = vec3(u);
  if ((b.grading.uniform_extent.array() < 0.0).any()) {
    problems.add(up, "must be >= 0 along every axis (m)");
  }
  if (axisym && b.grading.uniform_extent.y() != 0.0) {
    problems.add(up + "/1", "must be 0 for fe-axisym bodies: [r, 0, z] (m)");
  }
  const bool block =
      b.geometry.type == GeometryType::rectangle || b.geometry.type == GeometryType::box;
  if (!block) problems.add(up, "is for rectangle and box geometries only");
}

void parse_discretization(const json& d, BodySpec& b, const std::string& p, Problems& problems) {
  const std::string dp = at(p, "discretization");
  b.discretization = from_name(discretization_names, d.at("type").get<std::string>());
  const bool axisym = is_axisymmetric(b.discretization);
  if (const auto sp = d.find("sph"); sp != d.end()) {
    if (b.discretization != Discretization::sph) {
      problems.add(at(dp, "sph"), "only sph bodies take sph settings");
    }
    SphSettings& ss = b.sph;
    ss.kernel = value_or(*sp, "kernel", std::string("cubic-spline")) == "wendland-c2"
                    ? SphKernel::wendland_c2
                    : SphKernel::cubic_spline;
    ss.h_over_spacing = value_or(*sp, "h_over_spacing", ss.h_over_spacing);
    ss.visc_linear = value_or(*sp, "viscosity_linear", ss.visc_linear);
    ss.visc_quadratic = value_or(*sp, "viscosity_quadratic", ss.visc_quadratic);
    ss.hourglass_coefficient = value_or(*sp, "hourglass_coefficient", ss.hourglass_coefficient);
    ss.update_threshold = value_or(*sp, "update_threshold", ss.update_threshold);
    ss.max_h_growth = value_or(*sp, "max_h_growth", ss.max_h_growth);
    ss.deactivate_failed = value_or(*sp, "deactivate_failed", ss.deactivate_failed);
    b.lattice =
        value_or(*sp, "lattice", std::string("hcp")) == "cubic" ? Lattice::cubic : Lattice::hcp;
    b.sph_jitter = value_or(*sp, "jitter", 0.0);
    b.sph_boundary_layers = value_or(*sp, "boundary_layers", 3);
  }
  const bool has_count = d.contains("elements_across");
  const bool has_size = d.contains("element_size");
  if (has_count && has_size) {
    problems.add(dp, "give either elements_across or element_size, not both");
  } else if (!has_count && !has_size) {
    problems.add(dp, "needs elements_across or element_size");
  }
  b.elements_across = value_or(d, "elements_across", 0);
  b.element_size = has_count ? 0.0 : value_or(d, "element_size", 0.0);
  if (const auto s = d.find("sector"); s != d.end()) {
    b.sector = from_name(sector_names, s->get<std::string>());
    if (b.discretization == Discretization::fe_axisym) {
      problems.add(at(dp, "sector"), "only fe-hex and sph bodies have a sector");
    } else if (b.sector != SectorKind::full && b.geometry.type == GeometryType::box) {
      problems.add(at(dp, "sector"),
                   "only spheres and cylinders have sectors; set the box's extent");
    }
  }
  if (const auto g = d.find("grading"); g != d.end()) {
    const std::string fp = dp + "/grading/focus";
    b.grading.enabled = true;
    b.grading.ratio = g->at("ratio").get<double>();
    // Scene coordinates, [r, 0, z] for fe-axisym bodies (the model builder
    // turns them into the mesh generators' (r, z)).
    b.grading.focus = vec3(g->at("focus"));
    if (axisym && b.grading.focus.x() < 0.0) {
      problems.add(fp + "/0", "must be >= 0 for fe-axisym bodies: the radius (m)");
    }
    if (axisym && b.grading.focus.y() != 0.0) {
      problems.add(fp + "/1", "must be 0 for fe-axisym bodies: [r, 0, z] (m)");
    }
    if (const auto u = g->find("uniform_extent"); u != g->end()) {
      parse_uniform_extent(*u, b, axisym, dp + "/grading/uniform_extent", problems);
    }
  }
}

BodySpec parse_body(const json& j, const std::string& p, const std::filesystem::path& base_dir,
                    Problems& problems) {
  BodySpec b;
  b.name = j.at("name").get<std::string>();
  b.geometry = parse_geometry(j.at("geometry"));
  parse_discretization(j.at("discretization"), b, p, problems);
  check_geometry(b, p, problems);

  const std::optional<Material> material =
      resolve_material(j.at("material"), base_dir, at(p, "material"), problems);
  if (material) b.material = *material;

  const json& initial = member_or_empty(j, "initial");
  if (const auto v = initial.find("velocity"); v != initial.end()) {
    b.velocity = vec3(*v);
    if (is_axisymmetric(b.discretization)) {
      for (int i = 0; i < 2; ++i) {
        if (b.velocity[i] != 0.0) {
          problems.add(p + "/initial/velocity/" + std::to_string(i),
                       "must be 0 for fe-axisym bodies, which move along the axis (z) only (m/s)");
        }
      }
    }
  }
  if (const auto w = initial.find("angular_velocity"); w != initial.end()) {
    b.angular_velocity = vec3(*w);
    if (is_axisymmetric(b.discretization) && b.angular_velocity != Vec3::Zero()) {
      problems.add(p + "/initial/angular_velocity",
                   "must be [0, 0, 0] for fe-axisym bodies, which cannot spin (rad/s)");
    }
  }
  b.temperature = value_or(initial, "temperature", strength_references(b.material.strength).T_ref);
  b.seed = value_or(initial, "seed", 1ULL);

  const json& sw = member_or_empty(j, "switches");
  b.switches.damage = value_or(sw, "damage", true);
  b.switches.thermal_softening = value_or(sw, "thermal_softening", true);
  b.switches.rate_hardening = value_or(sw, "rate_hardening", true);
  b.switches.adiabatic_heating = value_or(sw, "adiabatic_heating", true);
  b.switches.heat_conduction = value_or(sw, "heat_conduction", false);
  if (b.switches.heat_conduction && b.discretization == Discretization::sph) {
    problems.add(
        p + "/switches/heat_conduction",
        "SPH bodies conduct no heat; set it false, or model the body with finite elements");
  }

  const json& hg = member_or_empty(j, "hourglass");
  b.hourglass = from_name(hourglass_names, value_or(hg, "type", std::string("viscous")));
  b.hourglass_coefficient = value_or(hg, "coefficient", 0.1);

  const json& av = member_or_empty(j, "artificial_viscosity");
  b.q_linear = value_or(av, "linear", 0.06);
  b.q_quadratic = value_or(av, "quadratic", 1.5);

  const json& er = member_or_empty(j, "erosion");
  b.erosion = value_or(er, "enabled", false);
  b.erosion_min_time_step = value_or(er, "min_time_step", 0.0);
  b.erosion_on_damage = value_or(er, "damage", true);
  return b;
}

json body_to_json(const BodySpec& b) {
  json d{{"type", name_of(discretization_names, b.discretization)}};
  if (b.element_size > 0.0) {
    d["element_size"] = b.element_size;
  } else {
    d["elements_across"] = b.elements_across;
  }
  if (b.discretization != Discretization::fe_axisym) d["sector"] = name_of(sector_names, b.sector);
  if (b.discretization == Discretization::sph) {
    const SphSettings& ss = b.sph;
    d["sph"] = {{"lattice", b.lattice == Lattice::cubic ? "cubic" : "hcp"},
                {"kernel", ss.kernel == SphKernel::wendland_c2 ? "wendland-c2" : "cubic-spline"},
                {"h_over_spacing", ss.h_over_spacing},
                {"viscosity_linear", ss.visc_linear},
                {"viscosity_quadratic", ss.visc_quadratic},
                {"hourglass_coefficient", ss.hourglass_coefficient},
                {"update_threshold", ss.update_threshold},
                {"max_h_growth", ss.max_h_growth},
                {"deactivate_failed", ss.deactivate_failed},
                {"jitter", b.sph_jitter},
                {"boundary_layers", b.sph_boundary_layers}};
  }
  if (b.grading.enabled) {
    d["grading"] = {{"focus", to_json_vec(b.grading.focus)}, {"ratio", b.grading.ratio}};
    if (!b.grading.uniform_extent.isZero()) {
      d["grading"]["uniform_extent"] = to_json_vec(b.grading.uniform_extent);
    }
  }
  return {
      {"name", b.name},
      {"material", material_to_json(b.material)},
      {"geometry", geometry_to_json(b.geometry)},
      {"discretization", std::move(d)},
      {"initial",
       {{"velocity", to_json_vec(b.velocity)},
        {"angular_velocity", to_json_vec(b.angular_velocity)},
        {"temperature", b.temperature},
        {"seed", b.seed}}},
      {"switches",
       {{"damage", b.switches.damage},
        {"thermal_softening", b.switches.thermal_softening},
        {"rate_hardening", b.switches.rate_hardening},
        {"adiabatic_heating", b.switches.adiabatic_heating},
        {"heat_conduction", b.switches.heat_conduction}}},
      {"hourglass",
       {{"type", name_of(hourglass_names, b.hourglass)}, {"coefficient", b.hourglass_coefficient}}},
      {"artificial_viscosity", {{"linear", b.q_linear}, {"quadratic", b.q_quadratic}}},
      {"erosion",
       {{"enabled", b.erosion},
        {"min_time_step", b.erosion_min_time_step},
        {"damage", b.erosion_on_damage}}},
  };
}

const BodySpec* find_body(const Scene& scene, const std::string& name) {
  for (const BodySpec& b : scene.bodies) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

// ---------------------------------------------------------------- boundaries

constexpr NameTable<HistoryInterpolation, 2> interpolation_names{{
    {HistoryInterpolation::linear, "linear"},
    {HistoryInterpolation::smooth_step, "smooth-step"},
}};
static_assert(names_in_order(interpolation_names));

// The schema checks the types and signs; here: as many velocities as times,
// times strictly increasing.
VelocityHistory parse_velocity_history(const json& j, const std::string& p, Problems& problems) {
  VelocityHistory h;
  h.time = j.at("time").get<std::vector<double>>();
  for (const json& v : j.at("velocity")) h.velocity.push_back(vec3(v));
  h.interpolation =
      from_name(interpolation_names, value_or(j, "interpolation", std::string("linear")));
  if (h.time.size() != h.velocity.size()) {
    problems.add(at(p, "velocity"), "has " + std::to_string(h.velocity.size()) +
                                        " rows but time has " + std::to_string(h.time.size()) +
                                        ": one velocity [vx, vy, vz] (m/s) per time (s)");
  }
  for (std::size_t k = 1; k < h.time.size(); ++k) {
    if (!(h.time[k] > h.time[k - 1])) {
      problems.add(at(at(p, "time"), k), "must exceed the time before it (" +
                                             std::to_string(h.time[k - 1]) +
                                             " s): times of a history increase strictly");
    }
  }
  return h;
}

json velocity_history_to_json(const VelocityHistory& h) {
  json velocity = json::array();
  for (const Vec3& v : h.velocity) velocity.push_back(to_json_vec(v));
  return {{"time", h.time},
          {"velocity", velocity},
          {"interpolation", name_of(interpolation_names, h.interpolation)}};
}

BoundarySpec parse_boundary(const json& j, const std::string& p, const Scene& scene,
                            Problems& problems) {
  BoundarySpec bc;
  bc.name = value_or(j, "name", std::string());
  bc.body = j.at("body").get<std::string>();
  bc.type = from_name(boundary_type_names, j.at("type").get<std::string>());
  if (const auto v = j.find("velocity"); v != j.end()) bc.velocity = vec3(*v);
  if (const auto h = j.find("history"); h != j.end()) {
    bc.history = parse_velocity_history(*h, at(p, "history"), problems);
  }
  if (bc.type == BoundaryType::velocity && !j.contains("velocity") && !bc.history) {
    problems.add(at(p, "velocity"),
                 "required field is missing: a velocity condition needs `velocity` (constant, "
                 "m/s) or `history` (tabulated, s and m/s)");
  }
  if (j.contains("velocity") && bc.history) {
    problems.add(at(p, "history"),
                 "give either `velocity` (constant) or `history` (tabulated), not both");
  }
  const json& components = member_or_empty(j, "components");
  if (!components.empty()) {
    bc.components = {false, false, false};
    for (std::size_t k = 0; k < components.size(); ++k) {
      const std::string c = components[k].get<std::string>();
      const std::size_t index = static_cast<std::size_t>(c[0] - 'x');
      if (bc.components[index]) {
        problems.add(at(at(p, "components"), k), "component " + c + " is listed twice");
      }
      bc.components[index] = true;
    }
  }
  const std::string on = j.at("on").get<std::string>();
  if (bc.type == BoundaryType::symmetry && on == "curved") {
    problems.add(at(p, "on"), "a symmetry condition needs a plane, not the curved surface");
  }
  const BodySpec* body = find_body(scene, bc.body);
  if (body == nullptr) {
    problems.add(at(p, "body"), "no body named \"" + bc.body + "\"");
    return bc;
  }
  if (is_axisymmetric(body->discretization)) {
    const std::optional<std::uint32_t> bit = boundary_bit(boundary_names_axisym, on);
    if (!bit) {
      problems.add(at(p, "on"), "fe-axisym body \"" + bc.body + "\" has boundaries axis, outer, " +
                                    "bottom, top and curved, not " + on);
    }
    bc.on = bit.value_or(0);
    if (bc.velocity.y() != 0.0) {
      problems.add(p + "/velocity/1", "must be 0 for fe-axisym bodies: [vr, 0, vz] (m/s)");
    }
    if (bc.history) {
      for (std::size_t k = 0; k < bc.history->velocity.size(); ++k) {
        if (bc.history->velocity[k].y() != 0.0) {
          problems.add(at(at(at(p, "history"), "velocity"), k) + "/1",
                       "must be 0 for fe-axisym bodies: [vr, 0, vz] (m/s)");
        }
      }
    }
    if (!components.empty() && bc.components[1]) {
      problems.add(at(p, "components"),
                   "fe-axisym bodies have components x (radial) and z (axial), not y");
    }
    bc.components[1] = false;
  } else {
    const std::optional<std::uint32_t> bit = boundary_bit(boundary_names_3d, on);
    if (!bit) {
      problems.add(at(p, "on"), on + " is a boundary of fe-axisym bodies; 3D body \"" + bc.body +
                                    "\" has x_min, x_max, y_min, y_max, z_min, z_max and curved");
    }
    bc.on = bit.value_or(0);
  }
  return bc;
}

json boundary_to_json(const BoundarySpec& bc, const Scene& scene) {
  const BodySpec* body = find_body(scene, bc.body);
  std::string on;
  const auto lookup = [&](const auto& table) {
    for (const auto& [bit, name] : table) {
      if (bit == bc.on) on = name;
    }
  };
  if (body != nullptr && is_axisymmetric(body->discretization)) {
    lookup(boundary_names_axisym);
  } else {
    lookup(boundary_names_3d);
  }
  json j{{"body", bc.body}, {"on", on}, {"type", name_of(boundary_type_names, bc.type)}};
  if (!bc.name.empty()) j["name"] = bc.name;
  if (bc.type == BoundaryType::velocity) {
    if (bc.history) {
      j["history"] = velocity_history_to_json(*bc.history);
    } else {
      j["velocity"] = to_json_vec(bc.velocity);
    }
    // Only a restriction is written (all components is the default).
    const bool axisym = body != nullptr && is_axisymmetric(body->discretization);
    json components = json::array();
    bool all = true;
    for (std::size_t c = 0; c < 3; ++c) {
      if (axisym && c == 1) continue;
      if (bc.components[c]) components.push_back(std::string(1, static_cast<char>('x' + c)));
      all = all && bc.components[c];
    }
    if (!all) j["components"] = components;
  }
  return j;
}

// ---------------------------------------------------------------- interactions

InteractionSpec parse_interaction(const json& j, const std::string& p, const Scene& scene,
                                  bool axisym, Problems& problems) {
  InteractionSpec in;
  in.type = from_name(interaction_names, j.at("type").get<std::string>());
  if (in.type == InteractionType::contact) {
    in.master = j.at("master").get<std::string>();
    in.slave = j.at("slave").get<std::string>();
    for (const char* side : {"master", "slave"}) {
      const std::string& name = side[0] == 'm' ? in.master : in.slave;
      if (find_body(scene, name) == nullptr) {
        problems.add(at(p, side), "no body named \"" + name + "\"");
      }
    }
    if (in.master == in.slave) {
      problems.add(at(p, "slave"), "must differ from master (self-contact is not available)");
    }
    in.method = from_name(contact_method_names, value_or(j, "method", std::string("lagrange")));
    in.penalty_stiffness = value_or(j, "penalty_stiffness", 0.0);
    in.friction = value_or(j, "friction", 0.0);
    in.solver = from_name(contact_solver_names, value_or(j, "solver", std::string("pgs")));
    // Two passes by default where both sides are FE and the contact is a
    // Lagrange one (see ContactSettings::two_pass); SPH pairs and penalty
    // springs keep one pass.
    const BodySpec* mb = find_body(scene, in.master);
    const BodySpec* sb = find_body(scene, in.slave);
    const bool fe_pair = mb != nullptr && sb != nullptr &&
                         mb->discretization != Discretization::sph &&
                         sb->discretization != Discretization::sph;
    in.two_pass = value_or(j, "two_pass", fe_pair && in.method == ContactMethod::lagrange);
    if (const auto a = j.find("adhesion"); a != j.end()) {
      in.adhesion = adhesion_from_json(*a);
      if (in.method != ContactMethod::lagrange) {
        problems.add(at(p, "adhesion"), "needs method \"lagrange\" (the links are multipliers)");
      }
      if (in.solver != ContactSolverKind::pgs) {
        problems.add(at(p, "adhesion"), "needs solver \"pgs\" (bonded rows)");
      }
    }
    if (in.friction > 0.0 && in.method == ContactMethod::lagrange &&
        in.solver == ContactSolverKind::active_set) {
      problems.add(at(p, "solver"), "active-set is frictionless: use pgs with friction > 0");
    }
    if (in.method != ContactMethod::penalty && j.contains("penalty_stiffness")) {
      problems.add(at(p, "penalty_stiffness"), "only with method \"penalty\"");
    }
    return in;
  }
  if (const auto bodies = j.find("bodies"); bodies != j.end()) {
    for (std::size_t i = 0; i < bodies->size(); ++i) {
      in.bodies.push_back(bodies->at(i).get<std::string>());
      if (find_body(scene, in.bodies.back()) == nullptr) {
        problems.add(at(at(p, "bodies"), i), "no body named \"" + in.bodies.back() + "\"");
      }
    }
  }
  in.point = vec3(j.at("point"));
  const Vec3 normal = vec3(j.at("normal"));
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    problems.add(at(p, "normal"), "must be non-zero (-)");
    return in;
  }
  in.normal = normal / length;
  if (axisym && (normal.x() != 0.0 || normal.y() != 0.0)) {
    problems.add(at(p, "normal"), "must be along z in an axisymmetric scene: [0, 0, nz] (-)");
  }
  return in;
}

json interaction_to_json(const InteractionSpec& in) {
  if (in.type == InteractionType::contact) {
    json j{{"type", name_of(interaction_names, in.type)},
           {"master", in.master},
           {"slave", in.slave},
           {"method", name_of(contact_method_names, in.method)},
           {"friction", in.friction},
           {"solver", name_of(contact_solver_names, in.solver)},
           {"two_pass", in.two_pass}};
    if (in.adhesion) j["adhesion"] = adhesion_to_json(*in.adhesion);
    if (in.method == ContactMethod::penalty) j["penalty_stiffness"] = in.penalty_stiffness;
    return j;
  }
  json j{{"type", name_of(interaction_names, in.type)},
         {"point", to_json_vec(in.point)},
         {"normal", to_json_vec(in.normal)}};
  if (!in.bodies.empty()) j["bodies"] = in.bodies;
  return j;
}

// ---------------------------------------------------------------- time, output

TimeSpec parse_time(const json& t) {
  TimeSpec ts;
  ts.end_time = t.at("end_time").get<double>();
  ts.dt = value_or(t, "dt", 0.0);
  ts.stability_coefficient = value_or(t, "stability_coefficient", ts.stability_coefficient);
  ts.max_steps = value_or(t, "max_steps", ts.max_steps);
  ts.min_time_step = value_or(t, "min_time_step", ts.min_time_step);
  ts.wall_clock_limit = value_or(t, "wall_clock_limit", ts.wall_clock_limit);
  ts.energy_balance_limit = value_or(t, "energy_balance_limit", ts.energy_balance_limit);
  return ts;
}

json time_to_json(const TimeSpec& ts, bool two_mass) {
  json j{{"end_time", ts.end_time},
         {"stability_coefficient", ts.stability_coefficient},
         {"max_steps", ts.max_steps},
         {"min_time_step", ts.min_time_step},
         {"wall_clock_limit", ts.wall_clock_limit},
         {"energy_balance_limit", ts.energy_balance_limit}};
  if (two_mass) j["dt"] = ts.dt;
  return j;
}

// ---------------------------------------------------------------- two-mass scenes

TwoMassSpec parse_two_mass(const json& j, const TimeSpec& time, Problems& problems) {
  TwoMassSpec t;
  t.M = j.at("M").get<double>();
  t.m = j.at("m").get<double>();
  t.k = j.at("k").get<double>();
  t.V0 = j.at("V0").get<double>();
  t.area = j.at("area").get<double>();
  t.adhesion = adhesion_from_json(j.at("adhesion"));
  // Every energy of the run is of the order of M V0^2 / 2: it must be a number.
  if (!std::isfinite(0.5 * t.M * t.V0 * t.V0)) {
    problems.add("/two_mass/V0",
                 "the kinetic energy M V0^2 / 2 must be finite in double precision (J)");
  }
  if (t.adhesion.activation != ActivationRule::none) {
    problems.add("/two_mass/adhesion/activation/rule",
                 "must be \"none\": rigid masses have no yield stress to drop");
  }
  // Central differences on the spring are stable for dt < 2 / omega.
  if (t.k > 0.0 && time.dt > 0.0) {
    const double dt_max = 2.0 * std::sqrt(t.m / t.k);
    if (!(time.dt < dt_max)) {
      problems.add("/time/dt", "must be < 2 sqrt(m / k) = " + std::to_string(dt_max) +
                                   " for a stable spring (s)");
    }
  }
  if (time.dt > time.end_time) problems.add("/time/dt", "must be <= end_time (s)");
  return t;
}

json two_mass_to_json(const TwoMassSpec& t) {
  return {{"M", t.M},   {"m", t.m},       {"k", t.k},
          {"V0", t.V0}, {"area", t.area}, {"adhesion", adhesion_to_json(t.adhesion)}};
}

OutputSpec parse_output(const json& o, double end_time, Problems& problems) {
  OutputSpec out;
  out.history_interval = value_or(o, "history_interval", 0.0);
  const auto times = o.find("snapshot_times");
  const auto count = o.find("snapshot_count");
  if (times != o.end() && count != o.end()) {
    problems.add("/output", "give snapshot_times or snapshot_count, not both");
  }
  if (times != o.end()) {
    for (std::size_t i = 0; i < times->size(); ++i) {
      const double t = times->at(i).get<double>();
      const std::string p = at("/output/snapshot_times", i);
      if (t > end_time) problems.add(p, "must be <= end_time (s)");
      if (!out.snapshot_times.empty() && !(t > out.snapshot_times.back())) {
        problems.add(p, "must be > the previous snapshot time (s)");
      }
      out.snapshot_times.push_back(t);
    }
  } else if (count != o.end()) {
    // n snapshots evenly spaced, the last at the end time.
    const long long n = count->get<long long>();
    for (long long i = 1; i <= n; ++i) {
      out.snapshot_times.push_back(
          i == n ? end_time : end_time * static_cast<double>(i) / static_cast<double>(n));
    }
  }
  return out;
}

json output_to_json(const OutputSpec& out) {
  return {{"snapshot_times", out.snapshot_times}, {"history_interval", out.history_interval}};
}

json scene_to_resolved_json(const Scene& scene) {
  json j{{"name", scene.name}, {"description", scene.description}};
  if (scene.two_mass) {
    j["two_mass"] = two_mass_to_json(*scene.two_mass);
    j["time"] = time_to_json(scene.time, true);
    j["output"] = output_to_json(scene.output);
    return j;
  }
  j["bodies"] = json::array();
  for (const BodySpec& b : scene.bodies) j["bodies"].push_back(body_to_json(b));
  j["boundary_conditions"] = json::array();
  for (const BoundarySpec& bc : scene.boundaries) {
    j["boundary_conditions"].push_back(boundary_to_json(bc, scene));
  }
  j["interactions"] = json::array();
  for (const InteractionSpec& in : scene.interactions) {
    j["interactions"].push_back(interaction_to_json(in));
  }
  j["time"] = time_to_json(scene.time, false);
  j["output"] = output_to_json(scene.output);
  return j;
}

// ---------------------------------------------------------------- overrides

[[noreturn]] void override_error(const std::string& override_text, const std::string& why) {
  throw InputError({{"", "override '" + override_text + "': " + why}});
}

bool is_array_index(const std::string& token) {
  if (token.empty() || token.size() > 9) return false;
  if (token.size() > 1 && token[0] == '0') return false;
  return std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void apply_override(json& doc, const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) override_error(text, "expected /json/pointer=VALUE");
  const std::string pointer_text = text.substr(0, eq);
  const std::string value_text = text.substr(eq + 1);
  if (pointer_text.empty() || pointer_text[0] != '/') {
    override_error(text, "the pointer must start with '/'");
  }
  json::json_pointer pointer;
  try {
    pointer = json::json_pointer(pointer_text);
  } catch (const json::exception&) {
    override_error(text, "bad JSON pointer '" + pointer_text + "'");
  }
  json value;
  try {
    value = json::parse(value_text);
  } catch (const json::parse_error&) {
    value = value_text;  // not JSON: a string, e.g. a material name
  } catch (const json::out_of_range&) {
    override_error(text, "the number is outside the range of a double");
  }

  // Walk to the parent. A missing key of an object becomes an empty object
  // (so `--set /time/max_time=1e-7` works on a scene without "time"); the
  // scene schema then refuses a key that is no field, naming it. Array
  // elements must exist.
  const json::json_pointer parent_pointer = pointer.parent_pointer();
  const std::string last = pointer.back();
  json* parent = &doc;
  std::string walked;
  std::vector<std::string> tokens;
  for (json::json_pointer p = parent_pointer; !p.empty(); p = p.parent_pointer()) {
    tokens.push_back(p.back());
  }
  std::reverse(tokens.begin(), tokens.end());
  for (const std::string& token : tokens) {
    walked += "/" + token;
    if (parent->is_object()) {
      const auto it = parent->find(token);
      parent = it == parent->end() ? &((*parent)[token] = json::object()) : &*it;
    } else if (parent->is_array()) {
      if (!is_array_index(token) || std::stoul(token) >= parent->size()) {
        override_error(
            text, walked + " does not exist (array of " + std::to_string(parent->size()) + ")");
      }
      parent = &(*parent)[std::stoul(token)];
    } else {
      override_error(text, walked + " does not exist (its parent is not an object or array)");
    }
  }
  const std::string target = parent_pointer.to_string() + "/" + last;
  if (parent->is_object()) {
    (*parent)[last] = std::move(value);
  } else if (parent->is_array()) {
    if (last == "-") {
      parent->push_back(std::move(value));
    } else if (is_array_index(last) && std::stoul(last) < parent->size()) {
      (*parent)[std::stoul(last)] = std::move(value);
    } else {
      override_error(text, "index " + last + " out of range for " +
                               (walked.empty() ? std::string("the document") : walked) +
                               " (array of " + std::to_string(parent->size()) + ")");
    }
  } else {
    override_error(text, (walked.empty() ? std::string("the document") : walked) +
                             " is not an object or array, so " + target + " cannot be set");
  }
}

// The impact run's view of an expanded particle_impact block (it carries the
// model the expansion chose under "model"). Throws InputError for a model
// name that is no fidelity.
ImpactSpec impact_spec(const json& block) {
  ImpactSpec impact;
  const json model = block.value("model", json::object());
  impact.substrate = model.value("rigid_substrate", false) ? "" : "substrate";
  impact.velocity = block.at("velocity").get<double>();
  impact.angle = block.value("angle", 0.0);
  impact.adaptive_end = !block.value("end_time", json("adaptive")).is_number();
  impact.max_eroded_fraction = block.value("max_eroded_fraction", impact.max_eroded_fraction);
  if (const auto name = model.find("name"); name != model.end()) {
    impact.model = parse<Fidelity>(name->get<std::string>());
    if (!impact.model) {
      throw InputError({{"/particle_impact/model/name",
                         "unknown model " + name->dump() + " (a fidelity other than auto)"}});
    }
  }
  impact.why = model.value("why", "");
  return impact;
}

// An expanded scene holds the impact velocity twice: in the particle body's
// initial velocity (what the run flies) and in the particle_impact block
// (what the verdict and the coefficient of restitution read). Copies that
// disagree (an override of one of them) are refused, naming both.
void check_impact_velocity(const Scene& scene, const ImpactSpec& impact) {
  const auto body = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                                 [&](const BodySpec& b) { return b.name == impact.particle; });
  if (body == scene.bodies.end()) return;
  const Vec3& v = body->velocity;
  const double speed = v.norm();
  const double angle =
      speed > 0.0 ? std::atan2(std::hypot(v.x(), v.y()), -v.z()) * 180.0 / std::numbers::pi : 0.0;
  const double tolerance = 1e-9 * std::max(speed, impact.velocity);
  Problems problems;
  const std::string where =
      "/bodies/" + std::to_string(body - scene.bodies.begin()) + "/initial/velocity";
  if (std::abs(speed - impact.velocity) > tolerance) {
    problems.add("/particle_impact/velocity",
                 "is " + std::to_string(impact.velocity) + " m/s but the particle body flies at " +
                     std::to_string(speed) + " m/s (" + where +
                     "): an expanded scene holds the velocity in both; set both, or set it in "
                     "a particle_impact scene and expand again");
  } else if (speed > 0.0 && std::abs(angle - impact.angle) > 1e-6) {
    problems.add("/particle_impact/angle", "is " + std::to_string(impact.angle) +
                                               " deg but the particle body flies at " +
                                               std::to_string(angle) + " deg from the normal (" +
                                               where + "): set both, or expand again");
  }
  if (!problems.list.empty()) throw InputError(std::move(problems.list));
}

}  // namespace

LoadedScene read_scene(const json& doc, const std::filesystem::path& base_dir) {
  validate_or_throw("scene", doc);
  if (doc.contains("particle_impact") && !doc.contains("bodies") && !doc.contains("two_mass")) {
    const ExpandedImpact expanded = expand_particle_impact(doc, base_dir);
    LoadedScene loaded = read_scene(expanded.scene, base_dir);
    const json& block = expanded.scene.at("particle_impact");
    loaded.scene.impact = impact_spec(block);
    loaded.resolved["particle_impact"] = block;
    return loaded;
  }
  Problems problems;
  LoadedScene loaded;
  Scene& scene = loaded.scene;
  scene.name = doc.at("name").get<std::string>();
  scene.description = value_or(doc, "description", std::string());

  if (const auto tm = doc.find("two_mass"); tm != doc.end()) {
    for (const char* key : {"bodies", "boundary_conditions", "interactions"}) {
      if (doc.contains(key)) {
        problems.add(at("", key), "a two_mass scene has no " + std::string(key) +
                                      "; give either two_mass or bodies");
      }
    }
    scene.time = parse_time(doc.at("time"));
    scene.two_mass = parse_two_mass(*tm, scene.time, problems);
    scene.output = parse_output(member_or_empty(doc, "output"), scene.time.end_time, problems);
    if (!scene.output.snapshot_times.empty()) {
      problems.add("/output",
                   "a two_mass scene has no field snapshots (its histories are in the "
                   "result file); remove snapshot_times / snapshot_count");
    }
    if (!problems.list.empty()) throw InputError(std::move(problems.list));
    loaded.resolved = scene_to_resolved_json(scene);
    return loaded;
  }

  const json& bodies = doc.at("bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string p = at("/bodies", i);
    scene.bodies.push_back(parse_body(bodies[i], p, base_dir, problems));
    const BodySpec& b = scene.bodies.back();
    for (std::size_t k = 0; k < i; ++k) {
      if (scene.bodies[k].name == b.name) {
        problems.add(at(p, "name"), "duplicate body name \"" + b.name + "\" (also /bodies/" +
                                        std::to_string(k) + "/name)");
        break;
      }
    }
    // One dimension per scene, set by the first body.
    const BodySpec& first = scene.bodies.front();
    if (is_axisymmetric(b.discretization) != is_axisymmetric(first.discretization)) {
      problems.add(p + "/discretization/type",
                   "all bodies of a scene are either fe-axisym or 3D: " +
                       name_of(discretization_names, b.discretization) + " cannot be mixed with " +
                       name_of(discretization_names, first.discretization) + " (/bodies/0)");
    }
  }
  const bool axisym = is_axisymmetric(scene.bodies.front().discretization);

  const json& bcs = member_or_empty(doc, "boundary_conditions");
  for (std::size_t i = 0; i < bcs.size(); ++i) {
    const std::string p = at("/boundary_conditions", i);
    scene.boundaries.push_back(parse_boundary(bcs[i], p, scene, problems));
    const std::string& name = scene.boundaries.back().name;
    for (std::size_t k = 0; k < i && !name.empty(); ++k) {
      if (scene.boundaries[k].name == name) {
        problems.add(at(p, "name"), "duplicate boundary-condition name \"" + name +
                                        "\" (also /boundary_conditions/" + std::to_string(k) +
                                        "/name)");
        break;
      }
    }
  }
  const json& interactions = member_or_empty(doc, "interactions");
  for (std::size_t i = 0; i < interactions.size(); ++i) {
    scene.interactions.push_back(
        parse_interaction(interactions[i], at("/interactions", i), scene, axisym, problems));
  }
  scene.time = parse_time(doc.at("time"));
  if (scene.time.dt != 0.0) {
    problems.add("/time/dt",
                 "only two_mass scenes take a fixed time step; FE scenes use the stability bound");
  }
  scene.output = parse_output(member_or_empty(doc, "output"), scene.time.end_time, problems);

  if (!problems.list.empty()) throw InputError(std::move(problems.list));
  loaded.resolved = scene_to_resolved_json(scene);
  // An already expanded impact scene (a campaign job, a resolved scene run
  // again): bodies plus the block with the model the expansion chose.
  if (const auto pi = doc.find("particle_impact"); pi != doc.end() && pi->contains("model")) {
    scene.impact = impact_spec(*pi);
    check_impact_velocity(scene, *scene.impact);
    loaded.resolved["particle_impact"] = *pi;
  }
  return loaded;
}

Scene scene_from_json(const json& doc, const std::filesystem::path& base_dir) {
  return read_scene(doc, base_dir).scene;
}

json resolved_scene_json(const json& doc, const std::filesystem::path& base_dir) {
  return read_scene(doc, base_dir).resolved;
}

void apply_overrides(json& doc, const std::vector<std::string>& overrides) {
  for (const std::string& text : overrides) apply_override(doc, text);
}

LoadedScene load_scene(const std::filesystem::path& file,
                       const std::vector<std::string>& overrides) {
  json doc = read_json_file(file);
  apply_overrides(doc, overrides);
  return read_scene(doc, file.parent_path());
}

}  // namespace splat
