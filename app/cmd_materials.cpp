// splat materials: the material library compiled into the binary.
//   splat materials              table of the library (SI units, stresses in
//                                MPa, moduli in GPa) with the strength law of
//                                each material, its parameters, then where
//                                each material's numbers come from
//   splat materials --json       the array of every library document
//   splat materials --show NAME  one document as written, a library name or a
//                                JSON file, checked first: an invalid one
//                                prints its violations to stderr, exit 2
//   splat materials --plot NAME [--out FILE]
//                                CSV of the flow stress against plastic
//                                strain at 1e-3, 1e3 and 1e6 /s and at 293 K
//                                and T_melt / 2, isothermal, from the law's
//                                own flow_stress (the solver's formula);
//                                scripts/plot_flow_stress.py draws it
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "app/commands.hpp"
#include "solver/input/embedded.hpp"
#include "solver/input/material_io.hpp"

namespace splat::app {

namespace {

struct MaterialsOptions {
  bool json = false;
  std::string show;
  std::string plot;
  std::string out;
};

std::string fixed(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

const char* initiation_text(DamageInitiation d) {
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

// Prints `text` from column `indent` on, broken between words before `width`.
void print_wrapped(const std::string& first, const std::string& text, std::size_t indent,
                   std::size_t width) {
  std::string line = first;
  line.resize(std::max(line.size(), indent), ' ');
  std::size_t start = 0;
  bool line_has_word = false;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (line_has_word && line.size() + 1 + word.size() > width) {
      std::printf("%s\n", line.c_str());
      line.assign(indent, ' ');
      line_has_word = false;
    }
    if (line_has_word) line += ' ';
    line += word;
    line_has_word = true;
    start = end + 1;
  }
  std::printf("%s\n", line.c_str());
}

// The unit a law parameter is shown in, and the factor from SI to it.
struct ShownUnit {
  const char* text;
  double per_si;
};

ShownUnit shown_unit(Quantity q) {
  switch (q) {
    case Quantity::yield_stress:
    case Quantity::hardening_stress:
      return {" MPa", 1e-6};
    case Quantity::rate:
      return {" 1/s", 1.0};
    case Quantity::room_temperature:
    case Quantity::melting_temperature:
      return {" K", 1.0};
    case Quantity::inverse_temperature:
      return {" 1/K", 1.0};
    case Quantity::inverse_pressure:
      return {" 1/GPa", 1e9};
    case Quantity::shear_modulus:
      return {" GPa", 1e-9};
    case Quantity::density:
      return {" kg/m^3", 1.0};
    case Quantity::molar_mass:
      return {" kg/mol", 1.0};
    case Quantity::dimensionless:
      break;
  }
  return {"", 1.0};
}

// The parameters of a strength law with their units (stresses in MPa).
std::string law_parameters(const StrengthModel& strength) {
  return std::visit(
      [](const auto& law) {
        std::string text;
        for (const auto& f : law.fields()) {
          const ShownUnit u = shown_unit(f.quantity);
          char buf[80];
          std::snprintf(buf, sizeof buf, "%s%s %g%s", text.empty() ? "" : ", ", f.name,
                        law.*f.member * u.per_si, u.text);
          text += buf;
        }
        return text;
      },
      strength);
}

int print_table() {
  using Row = std::vector<std::string>;
  std::vector<Row> rows = {
      {"name", "strength law", "rho", "E", "nu", "yield", "T_melt", "c_p", "damage"},
      {"", "", "kg/m^3", "GPa", "-", "MPa", "K", "J/(kg K)", "initiation"},
  };
  std::vector<Material> materials;
  for (const std::string& name : material_names()) {
    const Material m = load_material(name);
    rows.push_back({m.name, strength_model_name(m.strength), fixed(m.density, 0),
                    fixed(m.elastic.E / 1e9, 1), fixed(m.elastic.nu, 3),
                    fixed(initial_yield_stress(m.strength) / 1e6, 1),
                    fixed(strength_references(m.strength).T_melt, 0), fixed(m.thermal.c_p, 1),
                    initiation_text(m.damage.initiation)});
    materials.push_back(m);
  }
  const std::size_t columns = rows[0].size();
  std::vector<std::size_t> width(columns, 0);
  for (const Row& r : rows) {
    for (std::size_t c = 0; c < columns; ++c) width[c] = std::max(width[c], r[c].size());
  }
  for (const Row& r : rows) {
    std::string line;
    for (std::size_t c = 0; c < columns; ++c) {
      const std::string pad(width[c] - r[c].size(), ' ');
      const bool left = c <= 1 || c + 1 == columns;  // names left, numbers right
      if (c > 0) line += "  ";
      line += left ? r[c] + pad : pad + r[c];
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
  }
  std::printf("\nstrength laws (yield: flow stress at eps_p = 0, eps_dot_0 and T_ref):\n");
  for (const Material& m : materials) {
    print_wrapped("  " + m.name + ":",
                  std::string(strength_model_name(m.strength)) + ": " + law_parameters(m.strength),
                  20, 100);
  }
  std::printf("\nsources:\n");
  for (const Material& m : materials) print_wrapped("  " + m.name + ":", m.source, 20, 100);
  return 0;
}

// Library documents keep the field order of their files.
int print_all_documents() {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const std::string& name : material_names()) {
    for (const EmbeddedText& e : embedded_materials()) {
      if (e.name == name) all.push_back(nlohmann::ordered_json::parse(e.text));
    }
  }
  std::printf("%s\n", all.dump(2).c_str());
  return 0;
}

// The text of a library document or of a file, as written.
std::string document_text(const std::string& name_or_path) {
  for (const EmbeddedText& e : embedded_materials()) {
    if (e.name == name_or_path) return std::string(e.text);
  }
  std::ifstream in(name_or_path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int show_document(const std::string& name_or_path) {
  std::vector<SchemaViolation> problems;
  try {
    problems = material_violations(material_document(name_or_path));
  } catch (const InputError& e) {
    problems = e.violations();
  }
  if (problems.size() == 1 && problems[0].pointer.empty()) {  // not found, not JSON
    std::fprintf(stderr, "splat materials: %s\n", problems[0].message.c_str());
    return 2;
  }
  if (!problems.empty()) {
    std::fprintf(stderr, "splat materials: '%s' is not a valid material:\n", name_or_path.c_str());
    for (const SchemaViolation& v : problems) {
      std::fprintf(stderr, "  %s\n", to_string(v).c_str());
    }
    return 2;
  }
  std::string text = document_text(name_or_path);
  if (text.empty() || text.back() != '\n') text += '\n';
  std::fputs(text.c_str(), stdout);
  return 0;
}

// The flow-stress curves of --plot: plastic rates, 1/s, and temperatures, K
// (room temperature and half the law's melting temperature), plastic strain
// 0 to 1 in steps of 0.01.
constexpr double plot_rates[] = {1e-3, 1e3, 1e6};
constexpr int plot_points = 101;

int write_flow_stress_csv(const std::string& name_or_path, std::string out) {
  const Material m = load_material(name_or_path);
  if (out.empty()) out = m.name + "-flow-stress.csv";
  const double temperatures[] = {293.0, 0.5 * strength_references(m.strength).T_melt};
  std::ostringstream csv;
  csv << "strain_rate,temperature,plastic_strain,flow_stress\n";
  char line[128];
  for (double T : temperatures) {
    for (double rate : plot_rates) {
      for (int i = 0; i < plot_points; ++i) {
        const double eps_p = 0.01 * i;
        const double sigma = flow_stress(m.strength, ModelSwitches{}, eps_p, rate, T).value;
        std::snprintf(line, sizeof line, "%g,%.6g,%.2f,%.9g\n", rate, T, eps_p, sigma);
        csv << line;
      }
    }
  }
  std::ofstream f(out);
  f << csv.str();
  if (!f) {
    std::fprintf(stderr, "splat materials: error: cannot write '%s'\n", out.c_str());
    return 2;
  }
  std::printf("%s: %s flow stress, Pa, at %zu rates and 2 temperatures written to %s\n",
              m.name.c_str(), strength_model_name(m.strength), std::size(plot_rates), out.c_str());
  std::printf("plot: python3 scripts/plot_flow_stress.py %s\n", out.c_str());
  return 0;
}

}  // namespace

void register_materials(CLI::App& app, CommandTable& commands) {
  auto opts = std::make_shared<MaterialsOptions>();
  CLI::App* sub =
      app.add_subcommand("materials", "List the material library, or print one material document");
  CLI::Option* json_flag =
      sub->add_flag("--json", opts->json, "Print every library document as one JSON array");
  CLI::Option* show =
      sub->add_option("--show", opts->show,
                      "Print one material document (library name or JSON file) after checking it")
          ->excludes(json_flag);
  CLI::Option* plot =
      sub->add_option("--plot", opts->plot,
                      "Write the flow stress against plastic strain of one material (library "
                      "name or JSON file) at 1e-3, 1e3 and 1e6 /s, 293 K and T_melt / 2 as CSV")
          ->excludes(json_flag)
          ->excludes(show);
  sub->add_option("--out", opts->out, "CSV file of --plot (default NAME-flow-stress.csv)")
      ->needs(plot);
  commands.emplace_back(sub, [opts]() {
    if (!opts->plot.empty()) return write_flow_stress_csv(opts->plot, opts->out);
    if (!opts->show.empty()) return show_document(opts->show);
    if (opts->json) return print_all_documents();
    return print_table();
  });
}

}  // namespace splat::app
