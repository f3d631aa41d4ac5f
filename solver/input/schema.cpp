// Validation with valijson and translation of its reports.
//
// valijson says whether a document is valid and reports each failure as
// (instance path, description) with descriptions such as "Expected number
// greater than or equal to 0.000000" and no link to the schema node. To say
// `/strength/A: must be >= 0 (Pa)` we take the kind of failure from the
// description, find the schema nodes that apply at that instance path
// (following $ref, allOf, if/then/else and the matching branches of
// oneOf/anyOf), and re-check that kind of rule on those nodes, which gives the
// exact bound, the unit and every offending member (valijson names only the
// first unknown field of an object). Failures that valijson reports from
// oneOf/anyOf branches the document was clearly not meant for (their "model"
// const differs) find no violated node and are dropped; when no branch fits,
// the discriminating field is reported instead. Wrapper reports ("failed to
// validate against schema associated with property ...") are dropped when a
// more specific line covers their path, and kept in plain words otherwise, so
// an invalid document never yields an empty list.
#define VALIJSON_USE_EXCEPTIONS 1

// GCC 12 reports a false -Wrestrict in std::string::replace inlined from
// valijson's json_pointer.hpp (GCC bug 105329). The diagnostic is located in
// libstdc++, so the pragma must come before every include below.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

// valijson/exceptions.hpp includes <stdexcept> inside its namespace: include
// the standard headers first.
#include <stdexcept>
#include <string>

#include "solver/input/schema.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <regex>
#include <set>
#include <sstream>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "solver/input/embedded.hpp"

namespace splat {

using nlohmann::json;

std::string to_string(const SchemaViolation& v) {
  return v.pointer.empty() ? v.message : v.pointer + ": " + v.message;
}

std::ostream& operator<<(std::ostream& os, const SchemaViolation& v) {
  return os << '"' << to_string(v) << '"';
}

namespace {

std::string join_lines(const std::vector<SchemaViolation>& violations) {
  std::string out;
  for (const SchemaViolation& v : violations) {
    if (!out.empty()) out += '\n';
    out += to_string(v);
  }
  return out;
}

}  // namespace

InputError::InputError(std::vector<SchemaViolation> violations)
    : std::runtime_error(join_lines(violations)), violations_(std::move(violations)) {}

std::vector<SchemaViolation> prefixed(std::string_view prefix,
                                      std::vector<SchemaViolation> violations) {
  for (SchemaViolation& v : violations) v.pointer = std::string(prefix) + v.pointer;
  return violations;
}

namespace {

// ---------------------------------------------------------------------------
// Small helpers on JSON values and pointers.

std::string escape_pointer_token(std::string_view token) {
  std::string out;
  for (char c : token) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

// One step of an instance path: an object member or an array element.
struct PathStep {
  std::string key;
  std::optional<std::size_t> index;
};

std::string pointer_of(const std::vector<PathStep>& path) {
  std::string out;
  for (const PathStep& s : path) {
    out += '/';
    out += s.index ? std::to_string(*s.index) : escape_pointer_token(s.key);
  }
  return out;
}

std::string join_pointer(const std::string& parent, std::string_view key) {
  return parent + "/" + escape_pointer_token(key);
}

bool is_prefix_pointer(const std::string& prefix, const std::string& pointer) {
  if (prefix.empty()) return true;
  return pointer == prefix ||
         (pointer.size() > prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
          pointer[prefix.size()] == '/');
}

const json* child_value(const json* v, const PathStep& step) {
  if (v == nullptr) return nullptr;
  if (step.index) {
    return v->is_array() && *step.index < v->size() ? &(*v)[*step.index] : nullptr;
  }
  if (!v->is_object()) return nullptr;
  const auto it = v->find(step.key);
  return it == v->end() ? nullptr : &*it;
}

// Shortest text that reads back as the same number: 0.5, 300, 1e-06.
std::string number_text(const json& x) {
  if (x.is_number_integer() || x.is_number_unsigned()) return x.dump();
  const double d = x.get<double>();
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, d);
  return std::string(buf, res.ptr);
}

std::string value_text(const json& x) {
  return x.is_number() ? number_text(x) : x.dump();
}

std::string with_article(const std::string& type) {
  if (type == "null") return "null";
  const bool vowel = !type.empty() && std::string_view("aeiou").find(type[0]) != std::string::npos;
  return (vowel ? "an " : "a ") + type;
}

bool type_matches(const std::string& type, const json& v) {
  if (type == "object") return v.is_object();
  if (type == "array") return v.is_array();
  if (type == "string") return v.is_string();
  if (type == "boolean") return v.is_boolean();
  if (type == "null") return v.is_null();
  if (type == "number") return v.is_number();
  if (type == "integer") return v.is_number_integer() || v.is_number_unsigned();
  return true;
}

bool type_keyword_matches(const json& type, const json& v) {
  if (type.is_string()) return type_matches(type.get<std::string>(), v);
  if (type.is_array()) {
    return std::any_of(type.begin(), type.end(), [&](const json& t) {
      return t.is_string() && type_matches(t.get<std::string>(), v);
    });
  }
  return true;
}

std::size_t utf8_length(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(
      s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0U) != 0x80U; }));
}

bool regex_finds(const std::string& pattern, const std::string& text) {
  try {
    return std::regex_search(text, std::regex(pattern, std::regex::ECMAScript));
  } catch (const std::regex_error&) {
    return true;  // a pattern we cannot read cannot be used to blame the document
  }
}

std::optional<double> number_of(const json& s, const char* key) {
  const auto it = s.find(key);
  if (it == s.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

// ---------------------------------------------------------------------------
// The kinds of failure valijson 1.0 reports (validation_visitor.hpp).

enum class Failure {
  type,
  enumeration,
  constant,
  bound,
  multiple_of,
  min_length,
  max_length,
  pattern,
  item_count,
  too_many_items,
  unique_items,
  property_count,
  required,
  unknown_field,
  several_alternatives,
  negation,
  dependency,
  format,
  contains,
  no_alternative,  // oneOf / anyOf: no branch validated
  wrapper,         // "failed to validate against <child schema>": details come separately
  other,
};

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

Failure classify(std::string_view d) {
  if (starts_with(d, "Value type not permitted")) return Failure::type;
  if (starts_with(d, "Failed to match against any enum")) return Failure::enumeration;
  if (starts_with(d, "Failed to match expected value set by 'const'")) return Failure::constant;
  if (starts_with(d, "Expected number")) return Failure::bound;
  if (d.find("multiple of") != std::string_view::npos) return Failure::multiple_of;
  if (starts_with(d, "String should be no fewer")) return Failure::min_length;
  if (starts_with(d, "String should be no more")) return Failure::max_length;
  if (starts_with(d, "String should be a valid")) return Failure::format;
  if (starts_with(d, "Failed to match regex")) return Failure::pattern;
  if (starts_with(d, "Array should contain")) return Failure::item_count;
  if (starts_with(d, "Array contains more items") || starts_with(d, "Cannot validate item #")) {
    return Failure::too_many_items;
  }
  if (d.find("violate uniqueness") != std::string_view::npos) return Failure::unique_items;
  if (starts_with(d, "Object should have")) return Failure::property_count;
  if (starts_with(d, "Missing required property")) return Failure::required;
  if (starts_with(d, "Object contains a property that could not be validated")) {
    return Failure::unknown_field;
  }
  if (starts_with(d, "Failed to validate against exactly one")) {
    return Failure::several_alternatives;
  }
  if (starts_with(d, "Target should not validate")) return Failure::negation;
  if (starts_with(d, "Missing dependency")) return Failure::dependency;
  if (d.find("'contains' constraint") != std::string_view::npos) return Failure::contains;
  if (d.find("allowed by oneOf") != std::string_view::npos ||
      d.find("allowed by anyOf") != std::string_view::npos) {
    return Failure::no_alternative;
  }
  if (starts_with(d, "Failed to validate")) return Failure::wrapper;
  return Failure::other;
}

// valijson's sentence as a rule: lower-case first letter, no final period.
std::string plain_words(std::string d) {
  if (!d.empty() && d.back() == '.') d.pop_back();
  if (!d.empty() && d[0] >= 'A' && d[0] <= 'Z') d[0] = static_cast<char>(d[0] - 'A' + 'a');
  return d;
}

// ---------------------------------------------------------------------------
// Explainer: valijson reports in, SchemaViolations out.

class Explainer {
 public:
  Explainer(const json& schema, const json& doc) : root_(schema), doc_(doc) {}

  void add(const std::vector<std::string>& context, const std::string& description) {
    const std::vector<PathStep> path = path_of(context);
    const std::string pointer = pointer_of(path);
    const Failure kind = classify(description);
    raw_.push_back({pointer, plain_words(description)});
    if (kind == Failure::wrapper || kind == Failure::no_alternative) {
      if (kind == Failure::no_alternative) explain_no_alternative(path, pointer);
      wrappers_.push_back({pointer, plain_words(description)});
      return;
    }
    if (kind == Failure::other) {
      emit(pointer, plain_words(description));
      return;
    }
    const json* value = value_at(path);
    for (const json* node : locate(path)) explain(kind, *node, value, pointer);
  }

  std::vector<SchemaViolation> finish() {
    // A wrapper whose path no specific line covers is the only trace of
    // that failure: keep it.
    for (const SchemaViolation& w : wrappers_) {
      const bool covered = std::any_of(out_.begin(), out_.end(), [&](const SchemaViolation& v) {
        return is_prefix_pointer(w.pointer, v.pointer);
      });
      if (!covered) emit(w.pointer, w.message);
    }
    if (out_.empty()) {
      for (const SchemaViolation& r : raw_) emit(r.pointer, r.message);
    }
    return out_;
  }

 private:
  const json& root_;
  const json& doc_;
  std::vector<SchemaViolation> out_;
  std::set<std::pair<std::string, std::string>> seen_;
  std::vector<SchemaViolation> raw_;
  std::vector<SchemaViolation> wrappers_;

  static constexpr int max_depth = 64;  // guards against $ref cycles

  void emit(const std::string& pointer, const std::string& message) {
    if (seen_.insert({pointer, message}).second) out_.push_back({pointer, message});
  }

  // valijson contexts read {"<root>", "[strength]", "[A]"}; "[0]" is an index
  // when the instance there is an array.
  std::vector<PathStep> path_of(const std::vector<std::string>& context) const {
    std::vector<PathStep> path;
    const json* v = &doc_;
    for (std::size_t i = 0; i < context.size(); ++i) {
      std::string token = context[i];
      if (i == 0 && token == "<root>") continue;
      if (token.size() >= 2 && token.front() == '[' && token.back() == ']') {
        token = token.substr(1, token.size() - 2);
      }
      PathStep step{token, std::nullopt};
      if (v != nullptr && v->is_array() && !token.empty() &&
          std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        step.index = std::stoul(token);
      }
      v = child_value(v, step);
      path.push_back(std::move(step));
    }
    return path;
  }

  const json* value_at(const std::vector<PathStep>& path) const {
    const json* v = &doc_;
    for (const PathStep& s : path) v = child_value(v, s);
    return v;
  }

  // -- schema navigation ----------------------------------------------------

  const json* resolve_ref(const json& node) const {
    const auto it = node.find("$ref");
    if (it == node.end() || !it->is_string()) return nullptr;
    const std::string ref = it->get<std::string>();
    if (ref.empty() || ref[0] != '#') return nullptr;  // only local references
    try {
      const json::json_pointer ptr(ref.substr(1));
      return root_.contains(ptr) ? &root_.at(ptr) : nullptr;
    } catch (const json::exception&) {
      return nullptr;
    }
  }

  // Does `value` satisfy `s`? A small evaluator for if-conditions and for
  // choosing oneOf/anyOf branches; keywords it does not know pass.
  bool matches(const json& s, const json* v, int depth = 0) const {
    if (depth > max_depth) return true;
    if (s.is_boolean()) return s.get<bool>();
    if (!s.is_object() || v == nullptr) return true;
    if (s.contains("$ref")) {
      const json* target = resolve_ref(s);
      return target == nullptr || matches(*target, v, depth + 1);
    }
    if (const auto t = s.find("type"); t != s.end() && !type_keyword_matches(*t, *v)) return false;
    if (const auto c = s.find("const"); c != s.end() && *c != *v) return false;
    if (const auto e = s.find("enum");
        e != s.end() && e->is_array() && std::find(e->begin(), e->end(), *v) == e->end()) {
      return false;
    }
    if (v->is_number() && !bound_failures(s, *v).empty()) return false;
    if (v->is_string()) {
      const std::string str = v->get<std::string>();
      if (const auto p = s.find("pattern");
          p != s.end() && p->is_string() && !regex_finds(p->get<std::string>(), str)) {
        return false;
      }
      const auto len = static_cast<double>(utf8_length(str));
      if (len < number_of(s, "minLength").value_or(0.0)) return false;
      if (const auto mx = number_of(s, "maxLength"); mx && len > *mx) return false;
    }
    if (v->is_object()) {
      if (const auto r = s.find("required"); r != s.end() && r->is_array()) {
        for (const json& name : *r) {
          if (name.is_string() && !v->contains(name.get<std::string>())) return false;
        }
      }
      if (const auto p = s.find("properties"); p != s.end() && p->is_object()) {
        for (const auto& [key, sub] : p->items()) {
          if (const auto m = v->find(key); m != v->end() && !matches(sub, &*m, depth + 1)) {
            return false;
          }
        }
      }
      if (!unknown_fields(s, *v).empty()) return false;
    }
    if (v->is_array()) {
      if (const auto it = s.find("items"); it != s.end() && it->is_object()) {
        for (const json& item : *v) {
          if (!matches(*it, &item, depth + 1)) return false;
        }
      }
      const auto n = static_cast<double>(v->size());
      if (n < number_of(s, "minItems").value_or(0.0)) return false;
      if (const auto mx = number_of(s, "maxItems"); mx && n > *mx) return false;
    }
    if (const auto a = s.find("allOf"); a != s.end() && a->is_array()) {
      for (const json& sub : *a) {
        if (!matches(sub, v, depth + 1)) return false;
      }
    }
    if (const auto a = s.find("anyOf"); a != s.end() && a->is_array()) {
      if (std::none_of(a->begin(), a->end(),
                       [&](const json& sub) { return matches(sub, v, depth + 1); })) {
        return false;
      }
    }
    if (const auto a = s.find("oneOf"); a != s.end() && a->is_array()) {
      if (std::count_if(a->begin(), a->end(),
                        [&](const json& sub) { return matches(sub, v, depth + 1); }) != 1) {
        return false;
      }
    }
    if (const auto n = s.find("not"); n != s.end() && matches(*n, v, depth + 1)) return false;
    if (const auto i = s.find("if"); i != s.end()) {
      const char* branch = matches(*i, v, depth + 1) ? "then" : "else";
      if (const auto b = s.find(branch); b != s.end() && !matches(*b, v, depth + 1)) return false;
    }
    return true;
  }

  // Branch `b` of a oneOf/anyOf is meant for `v` unless one of its
  // properties with a const/enum (a discriminator such as "model") disagrees
  // with v, or is required and missing.
  bool branch_fits(const json& b, const json* v, int depth = 0) const {
    if (depth > max_depth) return true;
    if (!b.is_object()) return !b.is_boolean() || b.get<bool>();
    if (b.contains("$ref")) {
      const json* target = resolve_ref(b);
      return target == nullptr || branch_fits(*target, v, depth + 1);
    }
    if (v == nullptr) return true;
    if (const auto t = b.find("type"); t != b.end() && !type_keyword_matches(*t, *v)) return false;
    if (!v->is_object()) return true;
    const auto props = b.find("properties");
    if (props != b.end() && props->is_object()) {
      for (const auto& [key, sub] : props->items()) {
        if (!sub.contains("const") && !sub.contains("enum")) continue;
        const auto m = v->find(key);
        if (m == v->end()) {
          const auto req = b.find("required");
          if (req != b.end() && req->is_array() &&
              std::find(req->begin(), req->end(), key) != req->end()) {
            return false;
          }
        } else if (!matches(sub, &*m, depth + 1)) {
          return false;
        }
      }
    }
    if (const auto a = b.find("allOf"); a != b.end() && a->is_array()) {
      for (const json& sub : *a) {
        if (!branch_fits(sub, v, depth + 1)) return false;
      }
    }
    return true;
  }

  // All schema nodes that apply to `v`, starting from `s`.
  void expand(const json& s, const json* v, std::vector<const json*>& out, int depth = 0) const {
    if (depth > max_depth || !s.is_object()) return;
    if (s.contains("$ref")) {  // draft-07: siblings of $ref are ignored
      if (const json* target = resolve_ref(s)) expand(*target, v, out, depth + 1);
      return;
    }
    out.push_back(&s);
    if (const auto a = s.find("allOf"); a != s.end() && a->is_array()) {
      for (const json& sub : *a) expand(sub, v, out, depth + 1);
    }
    for (const char* key : {"anyOf", "oneOf"}) {
      const auto a = s.find(key);
      if (a == s.end() || !a->is_array()) continue;
      for (const json& sub : *a) {
        if (branch_fits(sub, v)) expand(sub, v, out, depth + 1);
      }
    }
    if (const auto i = s.find("if"); i != s.end()) {
      const char* branch = matches(*i, v) ? "then" : "else";
      if (const auto b = s.find(branch); b != s.end()) expand(*b, v, out, depth + 1);
    }
    if (const auto d = s.find("dependencies");
        d != s.end() && d->is_object() && v != nullptr && v->is_object()) {
      for (const auto& [key, sub] : d->items()) {
        if (sub.is_object() && v->contains(key)) expand(sub, v, out, depth + 1);
      }
    }
  }

  // Subschemas of node `s` for the member or element `step`.
  static std::vector<const json*> children(const json& s, const PathStep& step) {
    std::vector<const json*> out;
    if (step.index) {
      const auto items = s.find("items");
      if (items == s.end()) return out;
      if (items->is_object()) {
        out.push_back(&*items);
      } else if (items->is_array()) {
        if (*step.index < items->size()) {
          out.push_back(&(*items)[*step.index]);
        } else if (const auto add = s.find("additionalItems"); add != s.end() && add->is_object()) {
          out.push_back(&*add);
        }
      }
      return out;
    }
    if (const auto p = s.find("properties"); p != s.end() && p->is_object()) {
      if (const auto m = p->find(step.key); m != p->end()) out.push_back(&*m);
    }
    if (const auto pp = s.find("patternProperties"); pp != s.end() && pp->is_object()) {
      for (const auto& [pattern, sub] : pp->items()) {
        if (regex_finds(pattern, step.key)) out.push_back(&sub);
      }
    }
    if (out.empty()) {
      if (const auto add = s.find("additionalProperties"); add != s.end() && add->is_object()) {
        out.push_back(&*add);
      }
    }
    return out;
  }

  std::vector<const json*> locate(const std::vector<PathStep>& path) const {
    std::vector<const json*> nodes;
    const json* v = &doc_;
    expand(root_, v, nodes);
    for (const PathStep& step : path) {
      const json* child = child_value(v, step);
      std::vector<const json*> next;
      for (const json* node : nodes) {
        for (const json* sub : children(*node, step)) expand(*sub, child, next);
      }
      nodes = std::move(next);
      v = child;
    }
    return nodes;
  }

  // -- rules --------------------------------------------------------------

  static std::string unit_suffix(const json& node) {
    const auto u = node.find("unit");
    return u != node.end() && u->is_string() ? " (" + u->get<std::string>() + ")" : "";
  }

  static std::vector<std::string> bound_failures(const json& s, const json& v) {
    std::vector<std::string> out;
    if (!v.is_number()) return out;
    const double x = v.get<double>();
    struct Bound {
      const char* key;
      const char* words;
      bool (*broken)(double, double);
    };
    static constexpr Bound bounds[] = {
        {"minimum", "must be >= ", [](double a, double b) { return a < b; }},
        {"exclusiveMinimum", "must be > ", [](double a, double b) { return a <= b; }},
        {"maximum", "must be <= ", [](double a, double b) { return a > b; }},
        {"exclusiveMaximum", "must be < ", [](double a, double b) { return a >= b; }},
    };
    for (const Bound& b : bounds) {
      const auto it = s.find(b.key);
      if (it != s.end() && it->is_number() && b.broken(x, it->get<double>())) {
        out.push_back(b.words + number_text(*it) + unit_suffix(s));
      }
    }
    return out;
  }

  // Members of object `v` that node `s` closes out with additionalProperties: false.
  static std::vector<std::string> unknown_fields(const json& s, const json& v) {
    std::vector<std::string> out;
    const auto add = s.find("additionalProperties");
    if (add == s.end() || !add->is_boolean() || add->get<bool>() || !v.is_object()) return out;
    const auto props = s.find("properties");
    const auto patterns = s.find("patternProperties");
    for (const auto& [key, value] : v.items()) {
      if (props != s.end() && props->is_object() && props->contains(key)) continue;
      bool matched = false;
      if (patterns != s.end() && patterns->is_object()) {
        for (const auto& [pattern, sub] : patterns->items()) matched |= regex_finds(pattern, key);
      }
      if (!matched) out.push_back(key);
    }
    return out;
  }

  static std::string one_of_words(const json& values) {
    if (values.size() == 1) return "must be " + value_text(values[0]);
    std::string out = "must be one of ";
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) out += ", ";
      out += value_text(values[i]);
    }
    return out;
  }

  static std::string count_words(const json& s, const char* min_key, const char* max_key,
                                 const char* noun) {
    const auto lo = number_of(s, min_key);
    const auto hi = number_of(s, max_key);
    const auto n = [](double x) { return std::to_string(static_cast<long long>(x)); };
    if (lo && hi && *lo == *hi) return std::string("must have exactly ") + n(*lo) + " " + noun;
    if (lo && hi) return "must have " + n(*lo) + " to " + n(*hi) + " " + noun;
    if (lo) return "must have at least " + n(*lo) + " " + noun;
    return "must have at most " + n(hi.value_or(0.0)) + " " + noun;
  }

  void explain_type(const json& s, const json* v, const std::string& pointer) {
    const auto t = s.find("type");
    if (v == nullptr || t == s.end() || type_keyword_matches(*t, *v)) return;
    std::string want;
    if (t->is_string()) {
      want = with_article(t->get<std::string>());
    } else {
      for (std::size_t i = 0; i < t->size(); ++i) {
        if (i > 0) want += " or ";
        want += with_article((*t)[i].get<std::string>());
      }
    }
    emit(pointer, "must be " + want + ", got " + v->type_name());
  }

  void explain_length(const json& s, const json* v, const std::string& pointer) {
    if (v == nullptr || !v->is_string()) return;
    const auto len = static_cast<double>(utf8_length(v->get<std::string>()));
    const auto lo = number_of(s, "minLength");
    const auto hi = number_of(s, "maxLength");
    if (lo && len < *lo) {
      emit(pointer,
           *lo == 1.0 ? "must not be empty" : count_words(s, "minLength", "", "characters"));
    }
    if (hi && len > *hi) emit(pointer, count_words(s, "", "maxLength", "characters"));
  }

  void explain_item_count(const json& s, const json* v, const std::string& pointer) {
    if (v == nullptr || !v->is_array()) return;
    const auto n = static_cast<double>(v->size());
    const auto lo = number_of(s, "minItems");
    const auto hi = number_of(s, "maxItems");
    if ((lo && n < *lo) || (hi && n > *hi)) {
      emit(pointer,
           count_words(s, "minItems", "maxItems", "items") + ", got " + std::to_string(v->size()));
    }
  }

  void explain_too_many_items(const json& s, const json* v, const std::string& pointer) {
    const auto items = s.find("items");
    const auto add = s.find("additionalItems");
    if (v == nullptr || items == s.end() || !items->is_array() || add == s.end() ||
        !add->is_boolean() || add->get<bool>() || v->size() <= items->size()) {
      return;
    }
    emit(pointer, "must have at most " + std::to_string(items->size()) + " items, got " +
                      std::to_string(v->size()));
  }

  void explain_property_count(const json& s, const json* v, const std::string& pointer) {
    if (v == nullptr || !v->is_object()) return;
    const auto n = static_cast<double>(v->size());
    const auto lo = number_of(s, "minProperties");
    const auto hi = number_of(s, "maxProperties");
    if ((lo && n < *lo) || (hi && n > *hi)) {
      emit(pointer, count_words(s, "minProperties", "maxProperties", "fields"));
    }
  }

  void explain_required(const json& s, const json* v, const std::string& pointer) {
    const auto r = s.find("required");
    if (v == nullptr || !v->is_object() || r == s.end() || !r->is_array()) return;
    for (const json& name : *r) {
      if (name.is_string() && !v->contains(name.get<std::string>())) {
        emit(join_pointer(pointer, name.get<std::string>()), "required field is missing");
      }
    }
  }

  void explain_dependency(const json& s, const json* v, const std::string& pointer) {
    const auto d = s.find("dependencies");
    if (v == nullptr || !v->is_object() || d == s.end() || !d->is_object()) return;
    for (const auto& [key, needs] : d->items()) {
      if (!v->contains(key) || !needs.is_array()) continue;
      for (const json& name : needs) {
        if (name.is_string() && !v->contains(name.get<std::string>())) {
          emit(join_pointer(pointer, name.get<std::string>()),
               "required field is missing (needed with '" + key + "')");
        }
      }
    }
  }

  // Re-check rule `kind` of node `s` on value `v` and emit what is broken.
  void explain(Failure kind, const json& s, const json* v, const std::string& pointer) {
    if (!s.is_object()) return;
    switch (kind) {
      case Failure::type:
        explain_type(s, v, pointer);
        return;
      case Failure::enumeration: {
        const auto e = s.find("enum");
        if (v == nullptr || e == s.end() || !e->is_array() ||
            std::find(e->begin(), e->end(), *v) != e->end()) {
          return;
        }
        emit(pointer, one_of_words(*e));
        return;
      }
      case Failure::constant: {
        const auto c = s.find("const");
        if (v == nullptr || c == s.end() || *c == *v) return;
        emit(pointer, "must be " + value_text(*c));
        return;
      }
      case Failure::bound:
        if (v == nullptr) return;
        for (const std::string& m : bound_failures(s, *v)) emit(pointer, m);
        return;
      case Failure::multiple_of:
        if (const auto m = s.find("multipleOf"); m != s.end()) {
          emit(pointer, "must be a multiple of " + number_text(*m) + unit_suffix(s));
        }
        return;
      case Failure::min_length:
      case Failure::max_length:
        explain_length(s, v, pointer);
        return;
      case Failure::pattern: {
        const auto p = s.find("pattern");
        if (v == nullptr || !v->is_string() || p == s.end() || !p->is_string() ||
            regex_finds(p->get<std::string>(), v->get<std::string>())) {
          return;
        }
        emit(pointer, "must match the pattern " + p->dump());
        return;
      }
      case Failure::item_count:
        explain_item_count(s, v, pointer);
        return;
      case Failure::too_many_items:
        explain_too_many_items(s, v, pointer);
        return;
      case Failure::unique_items:
        if (s.value("uniqueItems", false)) emit(pointer, "items must all be different");
        return;
      case Failure::property_count:
        explain_property_count(s, v, pointer);
        return;
      case Failure::required:
        explain_required(s, v, pointer);
        return;
      case Failure::unknown_field:
        if (v == nullptr) return;
        for (const std::string& key : unknown_fields(s, *v)) {
          emit(join_pointer(pointer, key), "unknown field");
        }
        return;
      case Failure::several_alternatives:
        if (s.contains("oneOf")) {
          emit(pointer, "matches more than one of the alternatives allowed here");
        }
        return;
      case Failure::negation:
        if (s.contains("not")) emit(pointer, "must not match the schema given under 'not'");
        return;
      case Failure::dependency:
        explain_dependency(s, v, pointer);
        return;
      case Failure::format:
        if (const auto f = s.find("format"); f != s.end() && f->is_string()) {
          emit(pointer, "must be a valid " + f->get<std::string>());
        }
        return;
      case Failure::contains:
        if (s.contains("contains")) {
          emit(pointer,
               "must contain at least one item matching the schema given under 'contains'");
        }
        return;
      case Failure::no_alternative:
      case Failure::wrapper:
      case Failure::other:
        return;
    }
  }

  // No oneOf/anyOf branch validated. If every branch names a discriminating
  // field with a const/enum and none of them fits the document, say which
  // values that field may take; branch-specific failures are reported by
  // the lines that come with the branch that fits.
  void explain_no_alternative(const std::vector<PathStep>& path, const std::string& pointer) {
    const json* v = value_at(path);
    if (v == nullptr || !v->is_object()) return;
    for (const json* node : locate(path)) {
      for (const char* key : {"oneOf", "anyOf"}) {
        const auto a = node->find(key);
        if (a == node->end() || !a->is_array()) continue;
        std::vector<const json*> branches;
        for (const json& b : *a) {
          const json* r = &b;
          for (int i = 0; i < max_depth && r->is_object() && r->contains("$ref"); ++i) {
            r = resolve_ref(*r);
            if (r == nullptr) break;
          }
          if (r != nullptr) branches.push_back(r);
        }
        if (std::any_of(branches.begin(), branches.end(),
                        [&](const json* b) { return branch_fits(*b, v); })) {
          continue;
        }
        explain_discriminator(branches, *v, pointer);
      }
    }
  }

  void explain_discriminator(const std::vector<const json*>& branches, const json& v,
                             const std::string& pointer) {
    if (branches.empty() || !branches[0]->is_object()) return;
    const auto first = branches[0]->find("properties");
    if (first == branches[0]->end() || !first->is_object()) return;
    for (const auto& [key, unused] : first->items()) {
      json allowed = json::array();
      const bool everywhere = std::all_of(branches.begin(), branches.end(), [&](const json* b) {
        const json* sub = b->is_object() && b->contains("properties") &&
                                  (*b)["properties"].is_object() && (*b)["properties"].contains(key)
                              ? &(*b)["properties"][key]
                              : nullptr;
        if (sub == nullptr) return false;
        if (const auto c = sub->find("const"); c != sub->end()) {
          allowed.push_back(*c);
          return true;
        }
        if (const auto e = sub->find("enum"); e != sub->end() && e->is_array()) {
          for (const json& x : *e) allowed.push_back(x);
          return true;
        }
        return false;
      });
      if (!everywhere) continue;
      if (!v.contains(key)) {
        emit(join_pointer(pointer, key), "required field is missing");
      } else {
        emit(join_pointer(pointer, key), one_of_words(allowed));
      }
      return;
    }
  }
};

std::vector<SchemaViolation> run_validation(const valijson::Schema& compiled, const json& schema,
                                            const json& doc) {
  valijson::Validator validator;  // strong types: "1" is not a number
  valijson::ValidationResults results;
  const valijson::adapters::NlohmannJsonAdapter target(doc);
  if (validator.validate(compiled, target, &results)) return {};
  Explainer explainer(schema, doc);
  for (const valijson::ValidationResults::Error& e : results) {
    explainer.add(e.context, e.description);
  }
  return explainer.finish();
}

void compile(const json& schema, valijson::Schema& compiled, std::string_view name) {
  try {
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    const valijson::adapters::NlohmannJsonAdapter adapter(schema);
    parser.populateSchema(adapter, compiled);
  } catch (const std::exception& e) {
    throw std::invalid_argument("schema " + std::string(name) +
                                " is not a valid draft-07 JSON schema: " + e.what());
  }
}

// ---------------------------------------------------------------------------
// Cache of the embedded schemas: parsed and compiled on first use, never
// removed, so references handed out stay valid. valijson::Schema is only
// read during validation, so one compiled schema serves all threads.

struct CompiledSchema {
  json document;
  valijson::Schema schema;
};

const CompiledSchema& embedded_schema(std::string_view name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<CompiledSchema>, std::less<>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = cache.find(name); it != cache.end()) return *it->second;
  for (const EmbeddedText& e : embedded_schemas()) {
    if (e.name != name) continue;
    auto entry = std::make_unique<CompiledSchema>();
    try {
      entry->document = json::parse(e.text);
    } catch (const json::exception& ex) {
      throw std::invalid_argument("embedded schema " + std::string(name) +
                                  " is not valid JSON: " + ex.what());
    }
    compile(entry->document, entry->schema, name);
    return *cache.emplace(std::string(name), std::move(entry)).first->second;
  }
  std::string known;
  for (const std::string& n : schema_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown schema '" + std::string(name) + "' (known: " + known + ")");
}

// ---------------------------------------------------------------------------
// Parsing: positions of syntax errors, and fields given twice.

// Tracks the path through the document while nlohmann's parser reports
// events, to name the pointer of a repeated field and to stop at the depth
// limit before a deeper container is built (printing, hashing and validating
// a document recurse once per level).
class DuplicateFinder {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        begin_container(false);
        break;
      case json::parse_event_t::array_start:
        begin_container(true);
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        if (!frames_.empty()) frames_.pop_back();
        break;
      case json::parse_event_t::key: {
        Frame& top = frames_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second) {
          throw InputError({{pointer(), "duplicate field (given twice in the same object)"}});
        }
        break;
      }
      case json::parse_event_t::value:
        begin_value();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array;
    std::set<std::string> keys;
    std::string key;    // current member of an object
    std::size_t count;  // elements begun so far in an array
  };
  std::vector<Frame> frames_;

  // A value (scalar or container) starts inside the top container. Scalars
  // that end an object member also report `value`, which only matters for
  // arrays, where it counts the element.
  void begin_value() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().count;
  }

  void begin_container(bool is_array) {
    begin_value();
    if (frames_.size() >= std::size_t(k_max_json_depth)) {
      throw InputError(
          {{pointer(), "arrays and objects nested deeper than " + std::to_string(k_max_json_depth) +
                           " levels (the limit of JSON input)"}});
    }
    frames_.push_back({is_array, {}, {}, 0});
  }

  // The pointer of the value being read.
  std::string pointer() const { return pointer_with_next(false); }

 public:
  // The pointer of the scalar being read when the parser refuses it (it has
  // not been counted yet in its array).
  std::string pending_pointer() const { return pointer_with_next(true); }

 private:
  std::string pointer_with_next(bool next) const {
    std::string p;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool last = i + 1 == frames_.size();
      p += '/';
      p += f.is_array ? std::to_string(f.count - (next && last ? 0 : 1))
                      : escape_pointer_token(f.key);
    }
    return p;
  }
};

}  // namespace

std::vector<std::string> schema_names() {
  std::vector<std::string> names;
  for (const EmbeddedText& e : embedded_schemas()) names.emplace_back(e.name);
  std::sort(names.begin(), names.end());
  return names;
}

const json& schema_document(std::string_view name) {
  return embedded_schema(name).document;
}

std::vector<SchemaViolation> validate(std::string_view schema_name, const json& doc) {
  const CompiledSchema& s = embedded_schema(schema_name);
  return run_validation(s.schema, s.document, doc);
}

void validate_or_throw(std::string_view schema_name, const json& doc) {
  std::vector<SchemaViolation> v = validate(schema_name, doc);
  if (!v.empty()) throw InputError(std::move(v));
}

std::vector<SchemaViolation> validate_against(const json& schema, const json& doc) {
  valijson::Schema compiled;
  compile(schema, compiled, "given");
  return run_validation(compiled, schema, doc);
}

json parse_json_text(std::string_view text, std::string_view what) {
  DuplicateFinder finder;
  try {
    return json::parse(text.begin(), text.end(), std::ref(finder));
  } catch (const json::parse_error& e) {
    // nlohmann reads "... parse error at line 3, column 5: REASON".
    static const std::regex position(R"(at line (\d+), column (\d+): (.*))");
    const std::string full = e.what();
    std::smatch m;
    std::string where;
    std::string reason = full;
    if (std::regex_search(full, m, position)) {
      where = "line " + m[1].str() + ", column " + m[2].str();
      reason = m[3].str();
    } else {
      // Fall back on the byte offset.
      std::size_t line = 1;
      std::size_t column = 1;
      for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
        if (text[i] == '\n') {
          ++line;
          column = 1;
        } else {
          ++column;
        }
      }
      where = "line " + std::to_string(line) + ", column " + std::to_string(column);
    }
    throw InputError(
        {{"", "malformed JSON in " + std::string(what) + " at " + where + ": " + reason}});
  } catch (const json::exception& e) {
    if (e.id == 406) {
      // A number beyond double range (nlohmann's out_of_range.406, "number
      // overflow parsing '1e400'", thrown as its base class): named at the
      // field that holds it.
      static const std::regex number(R"(parsing '([^']*)')");
      const std::string full = e.what();
      std::smatch m;
      const std::string token = std::regex_search(full, m, number) ? m[1].str() : "a number";
      throw InputError({{finder.pending_pointer(),
                         "the number " + token + " in " + std::string(what) +
                             " is beyond the range of a double (magnitude at most 1.8e308)"}});
    }
    // Other refusals come without a position; drop nlohmann's
    // "[json.exception.KIND.N] " tag.
    std::string reason = e.what();
    if (const std::size_t tag_end = reason.find("] "); tag_end != std::string::npos) {
      reason.erase(0, tag_end + 2);
    }
    throw InputError({{"", "malformed JSON in " + std::string(what) + ": " + reason}});
  }
}

json read_json_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string name = "'" + path.string() + "'";
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError({{"", "cannot read " + name + ": no such file"}});
  if (fs::is_directory(st)) {
    throw InputError({{"", "cannot read " + name + ": it is a directory, not a JSON file"}});
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({{"", "cannot read " + name + ": permission denied or unreadable"}});
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError({{"", "cannot read " + name + ": read error"}});
  return parse_json_text(text.str(), "file " + name);
}

}  // namespace splat
